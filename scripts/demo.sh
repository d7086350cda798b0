#!/usr/bin/env bash
# make demo: the main job on an example, with its report.
# Until reconstruction lands (issue 4) the main job is the 2D distance fields
# with their medial axes; pictures go to out/demo/.
set -euo pipefail
dfrecon=${1:-build/bin/dfrecon}
echo "\$ dfrecon devices"
"$dfrecon" devices
echo
echo "\$ dfrecon info examples/torus.slices"
"$dfrecon" info examples/torus.slices
echo
echo "\$ dfrecon fields examples/torus.slices -o out/demo --png --json"
"$dfrecon" fields examples/torus.slices -o out/demo --png --json
echo
echo "Pictures of each slice's field, nearest contour and medial axes: out/demo/*.png"
