#!/usr/bin/env bash
# make demo: the main job on an example, with its report.
# Until reconstruction lands (issue 4) the main job is loading and validating
# a contour file; this prints the report a user would read first.
set -euo pipefail
dfrecon=${1:-build/bin/dfrecon}
echo "\$ dfrecon devices"
"$dfrecon" devices
echo
echo "\$ dfrecon info examples/torus.slices"
"$dfrecon" info examples/torus.slices
echo
echo "\$ dfrecon info examples/torus.slices --json"
"$dfrecon" info examples/torus.slices --json
