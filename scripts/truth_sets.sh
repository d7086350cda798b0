#!/usr/bin/env bash
# Makes the real-anatomy truth sets that `dfrecon-bench truth` measures
# against (docs/reconstruction.md, "Against known truth"): smoothed atlas-label
# surfaces from Debian's mricron-data, cut by parallel planes at spacings and
# offsets off the 1 mm voxel grid, along all three axes. Each set is a folder
# OUTDIR/NAME holding set-rtstruct.dcm (the contours), set-surface-cc.txt (the
# true volumes) and L<label>.ply (the true surfaces, patient LPS mm), made by
# scripts/truth_set.py (a copy of shared/tools/truth_set.py whose template
# RTSTRUCT is one of the test files). A set already there is kept.
# usage: scripts/truth_sets.sh OUTDIR
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
out=${1:?usage: truth_sets.sh OUTDIR}
templates=/usr/share/mricron/templates
# name            atlas                                  axis gap mm offset mm
sets=(
  "brodmann-axial-2.5     brodmann.nii.gz                    z 2.5 0.37"
  "brodmann-coronal-3     brodmann.nii.gz                    y 3.0 1.13"
  "brodmann-sagittal-1.5  brodmann.nii.gz                    x 1.5 0.61"
  "jhu-axial-2            JHU-WhiteMatter-labels-1mm.nii.gz  z 2.0 0.83"
  "jhu-coronal-5          JHU-WhiteMatter-labels-1mm.nii.gz  y 5.0 2.29"
)
for line in "${sets[@]}"; do
  read -r name atlas axis gap offset <<<"$line"
  [ -s "$out/$name/set-rtstruct.dcm" ] && continue
  if [ ! -f "$templates/$atlas" ]; then
    echo "truth_sets.sh: $templates/$atlas is missing (make setup installs mricron-data)" >&2
    exit 2
  fi
  mkdir -p "$out/$name.tmp"
  /usr/bin/python3 "$here/truth_set.py" --atlas "$templates/$atlas" --axis "$axis" --gap "$gap" \
    --offset "$offset" --surfaces "$out/$name.tmp" "$out/$name.tmp/set" >&2
  rm -rf "$out/$name"
  mv "$out/$name.tmp" "$out/$name"
done
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
