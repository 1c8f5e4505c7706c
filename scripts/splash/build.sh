#!/bin/sh
# Builds SPLASH-3 RADIOSITY (Hanrahan, Salzman & Aupperle's hierarchical radiosity, parallel; the
# program issue #19 measures against) from the mirror's snapshot of github.com/SakalisC/Splash-3,
# with one addition: gv_dump.c (beside this script), called once after a batch run, which writes
# each patch's geometry, reflectance, emittance and radiosity to $GV_SPLASH_DUMP when it is set.
# No SPLASH source file is edited in the repository; the build copy gets one call line inserted
# after the run's end time stamp. Flags: SPLASH-3's own (-O2 -pthread). Debian packages: gcc
# make m4. Prints the binary's path. B defaults to /tmp/splash3-build.
set -e
here=$(cd "$(dirname "$0")" && pwd)
B=${SPLASH_BUILD:-/tmp/splash3-build}
find_mirror() { local d; d=$here; while [ "$d" != / ]; do
  [ -d "$d/.mirror/SakalisC+Splash-3/repo" ] && { echo "$d/.mirror/SakalisC+Splash-3/repo"; return; }; d=$(dirname "$d"); done; }
GITDIR=${SPLASH_GIT:-$(find_mirror)}
[ -n "$GITDIR" ] || { echo "no Splash-3 snapshot in .mirror/SakalisC+Splash-3/repo above $here (fetch github:SakalisC/Splash-3, or set SPLASH_GIT)" >&2; exit 2; }
for p in gcc make m4; do command -v $p >/dev/null || apt-get install -y $p >/dev/null; done
rm -rf "$B" && mkdir -p "$B"
for f in $(git -C "$GITDIR" ls-tree -r --name-only HEAD codes | grep -E '^codes/(Makefile|pthread_macros/|apps/radiosity/)'); do
  mkdir -p "$B/$(dirname "$f")"
  git -C "$GITDIR" show "HEAD:$f" > "$B/$f"
done
R=$B/codes/apps/radiosity
cp "$here/gv_dump.c" "$R/gv_dump.c"
# The hook: after the batch run's end time stamp (the first "Print out running time" comment).
awk 'done == 0 && /Print out running time/ { print "            { extern void gv_dump_patches(void); gv_dump_patches(); }"; done = 1 } { print }' \
  "$R/rad_main.c.in" > "$R/rad_main.c.in.gv" && mv "$R/rad_main.c.in.gv" "$R/rad_main.c.in"
grep -q gv_dump_patches "$R/rad_main.c.in" || { echo "build.sh: the hook's anchor is gone from rad_main.c.in" >&2; exit 2; }
sed -i 's/^OBJS = \(.*\)$/OBJS = \1 gv_dump.o/' "$R/Makefile"
printf 'gv_dump.o: gv_dump.c $(HS)\n' >> "$R/Makefile"
make -C "$R" -j 2 > "$B/build.log" 2>&1 || { tail -30 "$B/build.log" >&2; exit 1; }
echo "$R/RADIOSITY"
