#!/bin/sh
# SPLASH-3 RADIOSITY and globalvis side by side on SPLASH's own scene (Hanrahan's furnished room,
# `-room`), both against one independent photon reference (issue #19's yardstick).
#   compare.sh GLOBALVIS OUT_DIR
# Env: SPLASH_BF (BF epsilons to run, SPLASH's -bf; its default 0.00015 takes minutes),
#      SPLASH_P (SPLASH threads, default 1), QUALITIES (globalvis --quality values),
#      GV_THREADS (default 1), PHOTONS (default 20000000), SKIP (triangles left out of SPLASH's
#      second L2: the rug lying in the floor's plane, which SPLASH leaves black; default 12,13).
# Prints one line per run: wall seconds (the whole process) and the area-weighted L2 of B-Ke.
set -e
[ $# -eq 2 ] || { echo "usage: compare.sh GLOBALVIS OUT_DIR" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
GV=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
OUT=$2
BF=${SPLASH_BF:-"0.015 0.005 0.0015 0.0005"}
P=${SPLASH_P:-1}
QUALITIES=${QUALITIES:-"draft low medium high"}
T=${GV_THREADS:-1}
SKIP=${SKIP:-12,13}
S=$("$here/build.sh")
mkdir -p "$OUT" && cd "$OUT"
# The scene: SPLASH's patches as it reads them (the geometry does not depend on the settings).
GV_SPLASH_DUMP=scene.txt "$S" -p 1 -room -batch -bf 0.5 -ae 100000 > /dev/null
python3 "$here/to_obj.py" scene.txt room.obj
cut -d' ' -f1-9 scene.txt > scene.geom
[ -d ref_raw ] || "$GV" photons room.obj -o ref_raw --photons "${PHOTONS:-20000000}" --no-contact-split --keep-hidden > /dev/null
[ -d ref ] || "$GV" photons room.obj -o ref --photons "${PHOTONS:-20000000}" > /dev/null
for bf in $BF; do
  d=splash_bf${bf}_p$P
  t=$( { GV_SPLASH_DUMP=$d.txt /usr/bin/time -f "%e" "$S" -p "$P" -room -batch -bf "$bf" > /dev/null; } 2>&1 | tail -1)
  cut -d' ' -f1-9 $d.txt | cmp -s - scene.geom ||
    { echo "$d: SPLASH listed its patches in another order than scene.txt" >&2; exit 1; }
  python3 "$here/to_obj.py" $d.txt $d.obj $d
  echo "SPLASH -p $P -bf $bf: $t s; $(python3 "$here/l2.py" $d.txt $d/radiosity.txt ref_raw/radiosity.txt --skip "$SKIP" | tr '\n' ';')"
done
for q in $QUALITIES; do
  d=gv_$q
  t=$( { /usr/bin/time -f "%e" "$GV" radiosity room.obj -o $d --no-pictures --quality $q --threads "$T" > /dev/null; } 2>&1 | tail -1)
  echo "globalvis --quality $q --threads $T: $t s; $("$GV" photons room.obj --reference ref --compare $d 2>&1 | grep -E 'L2 of|mean signed' | tr '\n' ';')"
done
