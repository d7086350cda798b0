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
echo "\$ dfrecon convert examples/two-rois.slices -o out/demo/two-rois.dcm   # a DICOM RT Structure Set"
"$dfrecon" convert examples/two-rois.slices -o out/demo/two-rois.dcm
"$dfrecon" info out/demo/two-rois.dcm | head -3
echo
echo "\$ dfrecon rasterize out/demo/two-rois.dcm --roi 1 --voxel-mm 1 -o out/demo/roi1.nrrd   # a label map for 3D Slicer"
"$dfrecon" rasterize out/demo/two-rois.dcm --roi 1 --voxel-mm 1 -o out/demo/roi1.nrrd
echo
echo "\$ dfrecon sdm out/demo/two-rois/*.ply -o out/demo/sdm   # how close are the two ROIs, everywhere"
"$dfrecon" sdm out/demo/two-rois/*.ply -o out/demo/sdm --size 256
echo
echo "\$ dfrecon check out/demo/y.ply"
"$dfrecon" check out/demo/y.ply
echo
echo "Meshes in out/demo/ open in MeshLab, ParaView, 3D Slicer and Blender."
