#!/bin/sh
# A second set of real levels, kept apart from make-test-levels.sh's so that it stays unseen
# while the code is tuned on the first: 6 Freedoom sector levels and 6 OpenArena arena levels
# (plain only), converted from Debian's game data into OUTDIR (default /tmp/gv-more-levels).
# Run once in a while as an outside check would: `vis` with its defaults, then `verify`.
#   scripts/make-more-levels.sh [OUTDIR]
#   for f in OUTDIR/*.obj; do globalvis vis $f -o out && globalvis verify out --rays 1000000 \
#     --unlisted-pairs 1000000; done
# First run: session 38 (docs/BENCHMARKS.md, "Twelve levels the code had never seen").
set -e
here=$(cd "$(dirname "$0")" && pwd)
out=${1:-/tmp/gv-more-levels}
wads=/usr/share/games/doom
oa=/usr/share/games/openarena/baseoa
# Debian packages: freedoom (0.12.1), openarena-081-maps, openarena-oacmp1.
for f in $wads/freedoom1.wad $wads/freedoom2.wad $oa/pak1-maps.pk3 $oa/z_oacmp-volume1-v3.pk3; do
  [ -f "$f" ] || { echo "missing $f: install the Debian packages freedoom, openarena-081-maps and openarena-oacmp1" >&2; exit 1; }
done
mkdir -p "$out"
python3 "$here/wad_to_obj.py" $wads/freedoom1.wad E1M3 E2M2 E3M1 -o "$out"
python3 "$here/wad_to_obj.py" $wads/freedoom2.wad MAP04 MAP06 MAP12 -o "$out"
for m in oa_dm6 czest1dm wrackdm17 oa_shouse; do
  python3 "$here/q3bsp_to_obj.py" "$oa/pak1-maps.pk3:maps/$m.bsp" -o "$out" --name "q3-$m"
done
for m in oacmpdm2 oacmpdm4; do
  python3 "$here/q3bsp_to_obj.py" "$oa/z_oacmp-volume1-v3.pk3:maps/$m.bsp" -o "$out" --name "q3-$m"
done
echo "wrote $(ls "$out"/*.obj | wc -l) OBJ files to $out"
