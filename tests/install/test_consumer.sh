#!/usr/bin/env bash
# Installs the build tree into a scratch prefix, checks what landed there,
# then configures, builds and runs tests/consumer against the installed
# package alone (its own build folder, no path into the sources): the sphere
# it reconstructs must be a valid solid with the sphere's volume.
#   test_consumer.sh BUILD_DIR SOURCE_DIR SCRATCH_DIR CXX_COMPILER
set -euo pipefail
build=$1 source=$2 scratch=$3 compiler=$4
prefix=$scratch/prefix
rm -rf "$scratch"
mkdir -p "$scratch"

cmake --install "$build" --prefix "$prefix" >"$scratch/install.log"
fail() { echo "test_consumer: $*" >&2; exit 1; }
for folder in kernels cl geometry io field shapes recon simplify sdm segment compare; do
  [ -f "$prefix/lib/libdfrecon_$folder.a" ] || fail "lib/libdfrecon_$folder.a not installed"
done
# The headers: the public API and the stage headers it includes, nothing
# else. Every installed header must be reachable from include/dfrecon/*.hpp
# by its #include lines; the consumer's build below shows none is missing.
reachable=$(cd "$prefix/include" && "${DFRECON_PYTHON_EXECUTABLE:-python3}" - <<'PY'
import os, re
seen, stack = set(), ["dfrecon/" + f for f in os.listdir("dfrecon") if f.endswith(".hpp")]
while stack:
    path = stack.pop()
    if path in seen or not os.path.isfile(path):
        continue
    seen.add(path)
    for included in re.findall(r'^\s*#\s*include\s*"([^"]+)"', open(path).read(), re.M):
        stack += [included, "dfrecon/" + included]
installed = {os.path.join(d, f)[2:] for d, _, fs in os.walk(".") for f in fs}
stray = sorted(installed - seen)
print("\n".join(stray))
PY
)
[ -z "$reachable" ] || fail "headers installed that the public API does not include: $reachable"
[ ! -e "$prefix/include/dfrecon/recon/SlabReconstructor.hpp" ] ||
  fail "an internal header (recon/SlabReconstructor.hpp) was installed"
[ ! -e "$prefix/include/dfrecon/app" ] && [ ! -e "$prefix/include/dfrecon/report" ] ||
  fail "the program's or the report layer's headers were installed"
for file in bin/dfrecon lib/cmake/dfrecon/dfreconConfig.cmake \
  lib/cmake/dfrecon/dfreconConfigVersion.cmake lib/cmake/dfrecon/dfreconTargets.cmake \
  lib/cmake/dfrecon/dfreconDependencies.cmake include/dfrecon/kernels/closest_point.cl \
  share/man/man1/dfrecon.1 share/bash-completion/completions/dfrecon; do
  [ -f "$prefix/$file" ] || fail "$file not installed"
done
# Our warning flags are ours: nothing exported names them.
if grep -l -e dfrecon_warnings -e -Wshadow "$prefix"/lib/cmake/dfrecon/*.cmake; then
  fail "the exported targets carry dfrecon_warnings"
fi
"$prefix/bin/dfrecon" --version >/dev/null || fail "the installed program does not run"
[ -f "$prefix/lib/libdfrecon_api.a" ] || fail "lib/libdfrecon_api.a not installed"
[ -f "$prefix/include/dfrecon/dfrecon.hpp" ] || fail "include/dfrecon/dfrecon.hpp not installed"
# The Python module, where it was built: imported from the prefix alone.
if [ -n "${DFRECON_PYTHON_EXECUTABLE:-}" ]; then
  init=$(find "$prefix/lib" -maxdepth 4 -path '*-packages/dfrecon/__init__.py' | head -n 1)
  [ -n "$init" ] || fail "the Python package is not installed under $prefix/lib"
  site=$(dirname "$(dirname "$init")")
  (cd "$scratch" && PYTHONPATH="$site" "$DFRECON_PYTHON_EXECUTABLE" -c \
    "import dfrecon, sys; assert dfrecon.__file__.startswith('$site'), dfrecon.__file__; print('python', dfrecon.__version__)") ||
    fail "the installed Python module does not import"
fi

cmake -S "$source/tests/consumer" -B "$scratch/build" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_COMPILER="$compiler" -DCMAKE_PREFIX_PATH="$prefix" >"$scratch/configure.log" 2>&1 ||
  { cat "$scratch/configure.log"; fail "configuring the consumer failed"; }
cmake --build "$scratch/build" >"$scratch/build.log" 2>&1 ||
  { cat "$scratch/build.log"; fail "building the consumer failed"; }
output=$("$scratch/build/consumer")
echo "$output"
# The reconstruction of 20 slices 2 mm apart, 64 points each: within 2 % of
# the sphere's volume (tests/recon hold it to its own tighter bounds).
echo "$output" | awk '$1 == "volumeMm3" && $5 == "validSolid" {
    error = ($2 - $4) / $4; if (error < 0) error = -error
    ok = $6 == 1 && error < 0.02 }
  END { exit ok ? 0 : 1 }' || fail "wrong volume or not a valid solid: $output"
rm -rf "$scratch"
