#!/usr/bin/env bash
# `make run`: the main job on the built-in default scene. The pipeline's later stages (cells,
# visibility, radiosity) are added here as they land; today it generates and describes the scene.
set -euo pipefail
gv="$1"
out="$2"
mkdir -p "$out"
echo "== globalvis: default scene (office, ~400 patches, the paper's scale) =="
"$gv" gen office -o "$out/office.obj"
"$gv" info "$out/office.obj"
echo
echo "Wrote $out/office.obj (+ .mtl). Open it in any OBJ viewer (e.g. Blender, MeshLab)."
echo "Pipeline status: import, generators and the geometry kernel exist; BSP cells, visibility"
echo "propagation and radiosity are not built yet (see docs/ARCHITECTURE.md)."
