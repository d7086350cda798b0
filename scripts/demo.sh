#!/usr/bin/env bash
# make demo: the main job on examples, with its report: contours in, closed
# surfaces out (out/demo/), checked.
set -euo pipefail
dfrecon=${1:-build/bin/dfrecon}
mkdir -p out/demo
echo "\$ dfrecon devices"
"$dfrecon" devices
echo
echo "\$ dfrecon info examples/y.slices"
"$dfrecon" info examples/y.slices
echo
echo "\$ dfrecon reconstruct examples/y.slices -o out/demo/y.ply --json"
"$dfrecon" reconstruct examples/y.slices -o out/demo/y.ply --json
echo
echo "\$ dfrecon reconstruct examples/two-rois.slices --all -o out/demo/two-rois"
"$dfrecon" reconstruct examples/two-rois.slices --all -o out/demo/two-rois
echo
echo "\$ dfrecon simplify out/demo/y.ply --max-error 0.5 --contours examples/y.slices -o out/demo/y-0.5mm.ply"
"$dfrecon" simplify out/demo/y.ply --max-error 0.5 --contours examples/y.slices -o out/demo/y-0.5mm.ply
echo
echo "\$ dfrecon check out/demo/y.ply"
"$dfrecon" check out/demo/y.ply
echo
echo "Meshes in out/demo/ open in MeshLab, ParaView, 3D Slicer and Blender."
