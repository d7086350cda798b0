#!/usr/bin/env bash
# make bench: every benchmark in bench/, each printing JSON lines.
set -euo pipefail
build=${1:-build}
for b in "$build"/bin/bench_*; do
    echo "# $(basename "$b")" >&2
    "$b"
done
