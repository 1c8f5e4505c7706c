#!/bin/sh
# The project's own test set of real levels that nobody here modelled (issue #17): 12 Freedoom
# sector levels and 14 OpenArena arena levels, plain and lit, converted from Debian's game data
# by wad_to_obj.py and q3bsp_to_obj.py into OUTDIR (default /tmp/gv-test-levels). The files are
# derived game data: they are made here, not kept in the repository.
#   scripts/make-test-levels.sh [OUTDIR]
#   globalvis bench --no-maps --no-offices --levels OUTDIR          # vis, verify, excess
#   globalvis bench --no-maps --no-offices --levels OUTDIR --radiosity   # and the lit variants
# With --more, 12 other levels instead (6 Freedoom, 6 OpenArena, plain only; default OUTDIR
# /tmp/gv-more-levels), kept apart so that they stay unseen while the code is tuned on the first
# set: run `vis` with its defaults and `verify --rays 1000000 --unlisted-pairs 1000000` on them
# now and then, as the outside checks do (first run: session 38, docs/BENCHMARKS.md).
#   scripts/make-test-levels.sh --more [OUTDIR]
# With --third, a third set of 16 (6 Freedoom, 10 OpenArena, plain only; default OUTDIR
# /tmp/gv-third-levels), first run unseen in session 40 (docs/BENCHMARKS.md): among them an
# outdoor island of 30,501 faces and a 242-face box, at both ends of the sizes.
#   scripts/make-test-levels.sh --third [OUTDIR]
set -e
here=$(cd "$(dirname "$0")" && pwd)
set_=test
case "$1" in --more | --third) set_=${1#--}; shift ;; esac
out=${1:-/tmp/gv-$set_-levels}
wads=/usr/share/games/doom
oa=/usr/share/games/openarena/baseoa
# Debian packages: freedoom (0.12.1), openarena-081-maps, openarena-oacmp1.
for f in $wads/freedoom1.wad $wads/freedoom2.wad $oa/pak1-maps.pk3 $oa/z_oacmp-volume1-v3.pk3; do
  [ -f "$f" ] || { echo "missing $f: install the Debian packages freedoom, openarena-081-maps and openarena-oacmp1" >&2; exit 1; }
done
mkdir -p "$out"
if [ $set_ = third ]; then
  python3 "$here/wad_to_obj.py" $wads/freedoom1.wad E1M5 E2M4 E3M6 -o "$out"
  python3 "$here/wad_to_obj.py" $wads/freedoom2.wad MAP08 MAP13 MAP18 -o "$out"
  for m in oa_minia delta suspended ce1m7 fan islanddm oa_spirit3 sleekgrinder oa_pvomit kaos2; do
    python3 "$here/q3bsp_to_obj.py" "$oa/pak1-maps.pk3:maps/$m.bsp" -o "$out" --name "q3-$m"
  done
  echo "wrote $(ls "$out"/*.obj | wc -l) OBJ files to $out"
  exit 0
fi
if [ $set_ = more ]; then
  python3 "$here/wad_to_obj.py" $wads/freedoom1.wad E1M3 E2M2 E3M1 -o "$out"
  python3 "$here/wad_to_obj.py" $wads/freedoom2.wad MAP04 MAP06 MAP12 -o "$out"
  for m in oa_dm6 czest1dm wrackdm17 oa_shouse; do
    python3 "$here/q3bsp_to_obj.py" "$oa/pak1-maps.pk3:maps/$m.bsp" -o "$out" --name "q3-$m"
  done
  for m in oacmpdm2 oacmpdm4; do
    python3 "$here/q3bsp_to_obj.py" "$oa/z_oacmp-volume1-v3.pk3:maps/$m.bsp" -o "$out" --name "q3-$m"
  done
  echo "wrote $(ls "$out"/*.obj | wc -l) OBJ files to $out"
  exit 0
fi
python3 "$here/wad_to_obj.py" $wads/freedoom1.wad E1M1 E1M4 E1M7 E2M1 E3M4 E4M1 -o "$out" --both
python3 "$here/wad_to_obj.py" $wads/freedoom2.wad MAP02 MAP05 MAP07 MAP10 MAP15 MAP20 -o "$out" --both
for m in oa_dm1 oa_dm3 oa_dm4 oa_dm5 oa_dm7 oa_ctf4ish aggressor kaos slimefac hydronex oa_bases3 q3dm6ish; do
  python3 "$here/q3bsp_to_obj.py" "$oa/pak1-maps.pk3:maps/$m.bsp" -o "$out" --name "q3-$m" --both
done
for m in oacmpdm1 oacmpdm3; do
  python3 "$here/q3bsp_to_obj.py" "$oa/z_oacmp-volume1-v3.pk3:maps/$m.bsp" -o "$out" --name "q3-$m" --both
done
echo "wrote $(ls "$out"/*.obj | wc -l) OBJ files to $out"
