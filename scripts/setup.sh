#!/usr/bin/env bash
# Installs the Debian 12 packages dfrecon needs (see DESIGN.md), only those
# that are missing, and says which. Idempotent: a second run installs nothing.
set -euo pipefail

# Packages installed with their recommends.
packages=(
  build-essential cmake pkg-config
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo
  libopenmesh-dev
  libopenvdb-dev libboost-iostreams-dev libtbb-dev libopenvdb-tools
  libdcmtk-dev
  libnifti2-dev libteem-dev zlib1g-dev
  libcgal-dev
  libgtest-dev
  libcli11-dev nlohmann-json3-dev
  clang libclang-rt-14-dev clang-format
)
# OpenCV pulls in a desktop's worth of recommends; we link core, imgproc and
# imgcodecs only.
packages_no_recommends=(libopencv-dev)

missing() {
  local out=()
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || out+=("$p")
  done
  echo "${out[@]:-}"
}

want=$(missing "${packages[@]}")
want_nr=$(missing "${packages_no_recommends[@]}")
if [ -z "$want" ] && [ -z "$want_nr" ]; then
  echo "setup: all dependencies present"
  exit 0
fi

SUDO=""
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
echo "setup: done"
