#!/usr/bin/env bash
# `make run`: the pipeline on the built-in default scene (the ~400-patch office, the paper's
# scale): generate, describe, cells (§3), visibility with blocker lists (§4-§5), an independent
# ray-casting check of it, and hierarchical radiosity. Everything lands in the output directory.
set -euo pipefail
gv="$1"
out="$2"
mkdir -p "$out"
# Each step's wall-clock time goes into $out/timings.json for the report.
timings="" current="" started=""
finish_step() {
  [ -n "$current" ] || return 0
  local seconds
  seconds=$(awk -v a="$started" -v b="$(date +%s.%N)" 'BEGIN { printf "%.3f", b - a }')
  timings+="${timings:+,}"$'\n'"    {\"name\": \"${current//\"/}\", \"seconds\": $seconds}"
  current=""
}
step() {
  finish_step
  current="$1" started=$(date +%s.%N)
  printf '\n== %s ==\n' "$1"
}

step "scene: office, default size"
"$gv" gen office -o "$out/office.obj"
"$gv" info "$out/office.obj"

step "cells and portals (paper §3, §7.1)"
# The cells `vis` uses: its default stop rule (--min-coverage 0.3) keeps furniture planes from
# splitting free space (see `globalvis vis --help`), so the viewer shows the same cells.
"$gv" cells "$out/office.obj" -o "$out/cells" --min-coverage 0.3

step "visibility and blocker lists (paper §4-§5, §7.2-7.3)"
# On the patches the radiosity step uses (cut along the outlines of the solids resting on them,
# scene/contact_split.h), so the viewer's links and the report's §7 figures are the radiosity's.
# A whole floor's or wall's shaft holds every piece of furniture in the room: on the whole
# patches 33 blockers per PARTIAL pair, on the cut ones 9.4 (docs/BENCHMARKS.md).
"$gv" vis "$out/office.obj" -o "$out/vis" --contact-split

step "independent check of the visibility by ray casting"
"$gv" verify "$out/vis" --rays 100000 --segments 20000 | tee "$out/vis/verify.txt"

# The paper's mode: links only for the pairs the visibility found, blockers kept in linespace
# tubes, rays only for PARTIAL links and only against their blockers (paper §6).
step "hierarchical radiosity (blockers visibility, paper §6 + HSA91)"
"$gv" radiosity "$out/office.obj" -o "$out/radiosity" --visibility blockers --quiet

finish_step
printf '{\n  "steps": [%s\n  ]\n}\n' "$timings" > "$out/timings.json"

step "report and viewer"
"$gv" view "$out"
"$gv" report "$out"
current=""

printf '\n== done ==\n'
echo "Outputs in $out/: report.html (the paper's §7 figures beside this run's; open it in a browser),"
echo "viewer.html (interactive: cells, portals, links, tubes and blockers), office.obj,"
echo "cells/ (cells.obj, portals.obj, cells.prt, stats.json), vis/ (patches.obj, visibility.txt, stats.json),"
echo "radiosity/ (radiosity.txt, elements.ply, stats.json, render.png and the Fig. 14 link pictures),"
echo "timings.json."
