#!/usr/bin/env bash
# Installs the Debian 12 packages dfrecon needs (docs/building.md), only those
# that are missing, and says which.
#
#   scripts/setup.sh build   what building and running the program needs
#                            (make demo, make build-program)
#   scripts/setup.sh         that, and what the tests, benchmarks, fuzzing
#                            and format check need; then makes the RTSTRUCT
#                            test fixtures in build/fixtures
#                            (scripts/fixtures.sh) (make setup, make test)
#   scripts/setup.sh bench   that, and the benchmarks' own data: the head CT
#                            in build/bench-fixtures (fixtures.sh bench)
#                            (make bench)
#
# Idempotent: a second run installs and regenerates nothing.
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
mode=${1:-all}
case "$mode" in
  build | all | bench) ;;
  *) echo "setup.sh: unknown mode '$mode' (build, all or bench)" >&2; exit 1 ;;
esac

# To build and run the program, installed with their recommends.
# The release build is clang with Ninja (CMakePresets.json) and links with
# lld (CMakeLists.txt); build-essential brings the C++ library clang links.
build_packages=(
  build-essential cmake pkg-config clang lld ninja-build
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo
  libopenmesh-dev
  libopenvdb-dev libboost-iostreams-dev libtbb-dev
  libdcmtk-dev
  libnifti2-dev libteem-dev zlib1g-dev
  libcgal-dev
  libcli11-dev nlohmann-json3-dev
  libpng-dev libtiff-dev
)
# OpenCV pulls in a desktop's worth of recommends; we link core and imgproc
# only (images are read and written with libpng and libtiff: io/images/ImageFiles). python3 makes the man page and bash completion at build
# time (scripts/help_pages.py); python3-dev, pybind11-dev and python3-numpy
# build the Python module (python/, docs/python.md).
build_packages_no_recommends=(
  libopencv-dev python3 openssl
  python3-dev pybind11-dev python3-numpy
)
# npm fetches the 3D viewer HTML reports embed (scripts/vendor_viewer.sh);
# Debian's where the machine has none of its own.
if ! command -v npm >/dev/null; then build_packages_no_recommends+=(npm); fi
# For the tests, benchmarks, fuzzing and format check, with recommends:
# GoogleTest, OpenVDB's tools, clang's sanitizer and fuzzer runtime,
# clang-format.
test_packages=(
  libgtest-dev libopenvdb-tools
  libclang-rt-14-dev clang-format
)
# Chromium opens the HTML reports headless in their tests. python3-vtk9
# reads our .vtk and .vtp files with VTK's own readers in the
# tests (tests/VtkRead.hpp; its recommends are Qt and MPI tooling). The rest
# make the RTSTRUCT test fixtures (scripts/fixtures.sh) and need none of
# theirs (pydicom's would add python3-pil, dicom3tools' ghostscript and
# netpbm). The Slurm daemons, client and munge run the array-job test
# (tests/app/slurm_array_test.sh) on a single-node Slurm; their recommends
# are the plugin development headers. python3-venv, -setuptools, -wheel and
# -pip let the pip test install the module into a venv offline
# (tests/python/pip_install.sh). mricron-data holds the atlases the
# truth benchmark cuts (scripts/truth_sets.sh, dfrecon-bench truth) and the
# compare tests read; its recommends are mricron itself.
test_packages_no_recommends=(
  chromium python3-vtk9 python3-pytest
  python3-venv python3-setuptools python3-wheel python3-pip
  python3-pydicom python3-numpy plastimatch insighttoolkit5-examples dicom3tools
  libcgal-demo
  slurmctld slurmd slurm-client munge
  mricron-data
)
# For the benchmarks alone: invesalius-examples holds the head CT whose
# structures the structure-set benchmark reconstructs (scripts/ct_structures.py
# thresholds it with python3-scipy).
bench_packages_no_recommends=(invesalius-examples python3-scipy)
packages=("${build_packages[@]}")
packages_no_recommends=("${build_packages_no_recommends[@]}")
if [ "$mode" != build ]; then
  packages+=("${test_packages[@]}")
  packages_no_recommends+=("${test_packages_no_recommends[@]}")
fi
if [ "$mode" = bench ]; then
  packages_no_recommends+=("${bench_packages_no_recommends[@]}")
fi

missing() {
  local out=()
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || out+=("$p")
  done
  echo "${out[@]:-}"
}

install_missing() {
  local want want_nr
  want=$(missing "${packages[@]}")
  want_nr=$(missing "${packages_no_recommends[@]}")
  if [ -z "$want" ] && [ -z "$want_nr" ]; then
    echo "setup: all dependencies present"
    return
  fi

  local SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  echo "setup: installing:${want:+ $want}${want_nr:+ $want_nr}"
  $SUDO apt-get update -qq
  if [ -n "$want" ]; then
    # shellcheck disable=SC2086
    $SUDO apt-get install -y -qq $want
  fi
  if [ -n "$want_nr" ]; then
    # shellcheck disable=SC2086
    $SUDO apt-get install -y -qq --no-install-recommends $want_nr
  fi
  echo "setup: packages installed"
}

install_missing
bash "$repo_root/scripts/vendor_viewer.sh" "$repo_root/build/vendor/three"
if [ "$mode" != build ]; then
  # Fast when they are already there (a stamp check).
  bash "$repo_root/scripts/fixtures.sh" "$repo_root/build/fixtures"
fi
if [ "$mode" = bench ]; then
  bash "$repo_root/scripts/fixtures.sh" "$repo_root/build/bench-fixtures" bench
fi
echo "setup: done"
