#!/usr/bin/env bash
# `make run`: the pipeline on the built-in default scene (the ~400-patch office, the paper's
# scale): generate, describe, cells (§3), visibility with blocker lists (§4-§5), an independent
# ray-casting check of it, and hierarchical radiosity. Everything lands in the output directory.
set -euo pipefail
gv="$1"
out="$2"
mkdir -p "$out"
step() { printf '\n== %s ==\n' "$1"; }

step "scene: office, default size"
"$gv" gen office -o "$out/office.obj"
"$gv" info "$out/office.obj"

step "cells and portals (paper §3, §7.1)"
"$gv" cells "$out/office.obj" -o "$out/cells"

# The visibility search enumerates portal sequences; with every furniture plane splitting the
# rooms (the default stop rule) that takes minutes, so the run uses the coarser stop rule.
step "visibility and blocker lists (paper §4-§5, §7.2-7.3)"
"$gv" vis "$out/office.obj" -o "$out/vis" --min-coverage 0.3

step "independent check of the visibility by ray casting"
"$gv" verify "$out/vis" --rays 100000 --segments 20000

step "hierarchical radiosity (rays visibility, HSA91)"
"$gv" radiosity "$out/office.obj" -o "$out/radiosity" --quiet

step "done"
echo "Outputs in $out/: office.obj, cells/ (cells.obj, portals.obj, stats.json),"
echo "vis/ (patches.obj, visibility.txt, stats.json), radiosity/ (radiosity.txt, elements.ply, stats.json)."
echo "Not built yet: linespace tubes and the paper's blocker-list radiosity mode, the HTML report"
echo "and viewer (see README.md, Status)."
