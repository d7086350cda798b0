#!/usr/bin/env bash
# Makes the whole-atlas sets that `dfrecon-bench atlases` reconstructs
# (issue 66: every area of 0.5 cc or more within 2 % of its contour volume):
# every label of AAL and AICHA from Debian's mricron-data, smoothed and cut
# by parallel planes off the 1 mm voxel grid by scripts/truth_set.py, as the
# truth sets are (scripts/truth_sets.sh). Each set is a folder OUTDIR/NAME
# holding set-rtstruct.dcm (the contours) and set-surface-cc.txt (each true
# surface's volume). A set already there is kept. About 10 s a set.
# usage: scripts/atlas_sets.sh OUTDIR
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
out=${1:?usage: atlas_sets.sh OUTDIR}
templates=/usr/share/mricron/templates
# name               atlas            axis gap mm
sets=(
  "aal-axial-3        aal.nii.gz       z 3"
  "aal-axial-2        aal.nii.gz       z 2"
  "aal-sagittal-4     aal.nii.gz       x 4"
  "aicha-coronal-3    AICHAmc.nii.gz   y 3"
)
for line in "${sets[@]}"; do
  read -r name atlas axis gap <<<"$line"
  [ -s "$out/$name/set-rtstruct.dcm" ] && [ -s "$out/$name/set-surface-cc.txt" ] && continue
  if [ ! -f "$templates/$atlas" ]; then
    echo "atlas_sets.sh: $templates/$atlas is missing (make setup installs mricron-data)" >&2
    exit 2
  fi
  rm -rf "$out/$name.tmp"
  mkdir -p "$out/$name.tmp"
  # Every label (--labels beyond the atlas's count takes them all).
  /usr/bin/python3 "$here/truth_set.py" --atlas "$templates/$atlas" --axis "$axis" --gap "$gap" \
    --labels 1000 --extra 0 "$out/$name.tmp/set" >&2
  rm -rf "$out/$name"
  mv "$out/$name.tmp" "$out/$name"
done
