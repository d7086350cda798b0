#!/usr/bin/env bash
# Makes the real-anatomy sets the benchmarks measure against, from Debian's
# mricron-data: atlas labels smoothed into surfaces and cut by parallel
# planes at spacings and offsets off the 1 mm voxel grid, along all three
# axes, by scripts/truth_set.py (a copy of shared/tools/truth_set.py whose
# template RTSTRUCT is one of the test files). Each set is a folder
# OUTDIR/NAME holding set-rtstruct.dcm (the contours) and
# set-surface-cc.txt (the true volumes). A set already there is kept.
#   scripts/truth_sets.sh OUTDIR           the truth sets of `dfrecon-bench
#       truth` (docs/reconstruction.md, "Against known truth"): some labels
#       each, with L<label>.ply (the true surfaces, patient LPS mm), and two
#       label-map sets made from them
#   scripts/truth_sets.sh --whole OUTDIR   the whole-atlas sets of
#       `dfrecon-bench atlases`: every label of AAL and AICHA, volumes only
#       (about 10 s a set)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
whole=false
if [ "${1:-}" = "--whole" ]; then
  whole=true
  shift
fi
out=${1:?usage: truth_sets.sh [--whole] OUTDIR}
templates=/usr/share/mricron/templates

# cut NAME ATLAS AXIS GAP_MM OFFSET_MM [truth_set.py options...]: one set.
cut() {
  local name=$1 atlas=$2 axis=$3 gap=$4 offset=$5
  shift 5
  [ -s "$out/$name/set-rtstruct.dcm" ] && [ -s "$out/$name/set-surface-cc.txt" ] && return 0
  if [ ! -f "$templates/$atlas" ]; then
    echo "truth_sets.sh: $templates/$atlas is missing (make setup installs mricron-data)" >&2
    exit 2
  fi
  rm -rf "$out/$name.tmp"
  mkdir -p "$out/$name.tmp"
  /usr/bin/python3 "$here/truth_set.py" --atlas "$templates/$atlas" --axis "$axis" --gap "$gap" \
    --offset "$offset" "$@" "$out/$name.tmp/set" >&2
  rm -rf "$out/$name"
  mv "$out/$name.tmp" "$out/$name"
}

if $whole; then
  # Every label (--labels beyond the atlas's count takes them all).
  cut aal-axial-3     aal.nii.gz     z 3 0.37 --labels 1000 --extra 0
  cut aal-axial-2     aal.nii.gz     z 2 0.37 --labels 1000 --extra 0
  cut aal-sagittal-4  aal.nii.gz     x 4 0.37 --labels 1000 --extra 0
  cut aicha-coronal-3 AICHAmc.nii.gz y 3 0.37 --labels 1000 --extra 0
  exit 0
fi

cut brodmann-axial-2.5    brodmann.nii.gz                   z 2.5 0.37 --surfaces "$out/brodmann-axial-2.5.tmp"
cut brodmann-coronal-3    brodmann.nii.gz                   y 3.0 1.13 --surfaces "$out/brodmann-coronal-3.tmp"
cut brodmann-sagittal-1.5 brodmann.nii.gz                   x 1.5 0.61 --surfaces "$out/brodmann-sagittal-1.5.tmp"
cut jhu-axial-2           JHU-WhiteMatter-labels-1mm.nii.gz z 2.0 0.83 --surfaces "$out/jhu-axial-2.tmp"
cut jhu-coronal-5         JHU-WhiteMatter-labels-1mm.nii.gz y 5.0 2.29 --surfaces "$out/jhu-coronal-5.tmp"

# Label-map sets (issue 66): a set's true surfaces voxelised at 1 mm and
# contoured from the voxels, as segmentation tools export label maps
# (scripts/labelmap_truth_set.py; it needs the dfrecon program: $DFRECON,
# else build/bin/dfrecon).
dfrecon=${DFRECON:-$here/../build/bin/dfrecon}
labelmaps=(
  "brodmann-labelmap-1  brodmann-axial-2.5"
  "jhu-labelmap-1       jhu-axial-2"
)
for line in "${labelmaps[@]}"; do
  read -r name source <<<"$line"
  [ -s "$out/$name/set-rtstruct.dcm" ] && continue
  /usr/bin/python3 "$here/labelmap_truth_set.py" "$out/$source" "$out/$name" "$dfrecon" >&2
done
