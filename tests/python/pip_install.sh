#!/usr/bin/env bash
# `pip install .` as a user does it, offline: a fresh venv of Debian's python3
# (its NumPy and setuptools through --system-site-packages), pip without build
# isolation (nothing to download), the project's CMake build reused
# (DFRECON_CMAKE_BUILD_DIR), then `import dfrecon` from outside the source
# tree reconstructs a box through the installed package.
# Usage: pip_install.sh SOURCE_DIR CMAKE_BUILD_DIR PYTHON
set -euo pipefail
src=$1 build=$2 python=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$python" -m venv --system-site-packages "$work/venv"
DFRECON_CMAKE_BUILD_DIR=$build DFRECON_PIP_BUILD_BASE=$work/pip-build \
  "$work/venv/bin/pip" install --disable-pip-version-check --no-build-isolation --no-index \
  --no-deps -q "$src"
cd "$work"
"$work/venv/bin/python" - <<'PY'
import os, sys
import numpy as np
import dfrecon
where = os.path.dirname(dfrecon.__file__)
assert "site-packages" in where, where  # the installed copy, not the tree
square = np.array([[0, 0], [10, 0], [10, 10], [0, 10]], dtype=float)
rs = dfrecon.StructureSet.from_contours(
    {"Box": [np.column_stack([square, np.full(4, z)]) for z in (0.0, 2.0, 4.0)]})
mesh = dfrecon.reconstruct(rs, "Box")
assert mesh.valid_solid
print("installed", dfrecon.__version__, "in", where, "box", round(mesh.volume_cc, 3), "cc")
PY
"$work/venv/bin/pip" --disable-pip-version-check show -q dfrecon >/dev/null
