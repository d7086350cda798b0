#!/usr/bin/env bash
# Makes the DICOM RT Structure Set fixtures for the RTSTRUCT reader tests from
# data that Debian packages ship (scripts/setup.sh installs them and calls
# this; nothing here is written by hand):
#
#   OUTDIR/pydicom/rtstruct.dcm      python3-pydicom's test RTSTRUCT, copied
#   OUTDIR/kmeans/                   insighttoolkit5-examples' 7-label k-means
#                                    segmentation (128x128x62, 2x2x3 mm,
#                                    CORONAL slices: its k axis runs along -y)
#       labels.nii.gz                the label volume, copied
#       masks/label_N.nrrd           one binary mask per label (plastimatch
#                                    threshold)
#       ss.nrrd, ss.txt              the masks as one structure-set image (bit
#                                    N = label N) and its list: this fixes the
#                                    ROI order (--input-prefix would number
#                                    ROIs in readdir order)
#       dicom/image0000..0061.dcm    reference series (the T1 the labels came
#                                    from, as CT), dicom/rtss.dcm the RTSTRUCT
#                                    (plastimatch convert --output-dicom)
#       rtstruct.dcm                 hard link to dicom/rtss.dcm
#       labels.json                  per label: voxel count, voxel and label
#                                    volume, ROI name/number/contour count
#                                    (scripts/label_stats.py)
#       dciodvfy.txt                 dicom3tools' check of rtstruct.dcm
#       *.log                        plastimatch's output
#   OUTDIR/kmeans_axial/             the same voxels with identity direction
#                                    cosines and origin (-127.3,-127.7,-90.1):
#                                    axial planes 3 mm apart, coordinates that
#                                    plastimatch writes as float32 digits
#                                    ("-3.0999999"); same files
#   OUTDIR/ct_head/ (bench)          invesalius-examples' head CT (Cranium.inv3)
#                                    at 512 x 512 x 108, 0.48 x 0.48 x 1.5 mm,
#                                    thresholded (scripts/ct_structures.py):
#                                    BODY, AIRWAY, BONE; dicom/ the CT series
#                                    and rtss.dcm, rtstruct.dcm, ss.txt
#   OUTDIR/meshes/NAME.off           meshes from libcgal-demo's data.tar.gz
#                                    (surface distance map scenes, geodesic
#                                    benchmarks): femur, bunny00, armadillo,
#                                    refined_elephant, elephant, blobby, eight,
#                                    sphere, cube, knot1 (all closed, manifold)
#
# Usage: scripts/fixtures.sh OUTDIR [tests|bench]
#   tests (default)  everything above but ct_head
#   bench            ct_head alone (the benchmarks' data; make bench)
# Idempotent: skips when OUTDIR/.complete holds this script's stamp (its and
# label_stats.py's hashes and the source packages' versions). Builds in a
# temporary folder beside OUTDIR and renames it at the end, so a failed run
# leaves no half-made OUTDIR.
set -euo pipefail

if [ $# -lt 1 ] || [ $# -gt 2 ]; then
  echo "usage: $0 OUTDIR [tests|bench]" >&2
  exit 2
fi
which=${2:-tests}
case "$which" in
  tests | bench) ;;
  *) echo "fixtures: unknown selection '$which' (tests or bench)" >&2; exit 2 ;;
esac
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
out=$1
python=/usr/bin/python3 # Debian's, with python3-numpy and python3-pydicom
source_packages=(plastimatch python3-pydicom python3-numpy insighttoolkit5-examples dicom3tools
  libcgal-demo)
if [ "$which" = bench ]; then source_packages+=(invesalius-examples python3-scipy); fi

stamp() {
  echo "fixtures v1 $which"
  sha256sum "$here/fixtures.sh" "$here/label_stats.py" "$here/ct_structures.py" | awk '{print $1}'
  for p in "${source_packages[@]}"; do
    echo "$p $(dpkg-query -W -f='${Version}' "$p" 2>/dev/null || echo none)"
  done
}
want_stamp=$(stamp)
if [ -f "$out/.complete" ] && [ "$(cat "$out/.complete")" = "$want_stamp" ]; then
  echo "fixtures: up to date in $out"
  exit 0
fi

die() {
  echo "fixtures: $*" >&2
  exit 1
}
command -v plastimatch >/dev/null || die "plastimatch missing (scripts/setup.sh installs it)"
"$python" -c 'import numpy, pydicom' 2>/dev/null ||
  die "$python lacks numpy or pydicom (python3-numpy, python3-pydicom)"
# One file of a package, found by the end of its path.
package_file() {
  local f
  f=$(dpkg -L "$1" 2>/dev/null | grep -E "/$2\$" | head -n 1) || true
  if [ -z "$f" ] || [ ! -f "$f" ]; then die "no $2 in package $1"; fi
  echo "$f"
}
pydicom_rtstruct=$(package_file python3-pydicom rtstruct.dcm)
kmeans_labels=$(package_file insighttoolkit5-examples KmeansTest_T1KmeansPrelimSegmentation.nii.gz)
kmeans_t1=$(package_file insighttoolkit5-examples KmeansTest_T1UCharRaw.nii.gz)
cgal_data=$(package_file libcgal-demo data.tar.gz)
if [ "$which" = bench ]; then
  cranium=$(package_file invesalius-examples Cranium.inv3)
  "$python" -c 'import scipy' 2>/dev/null || die "$python lacks scipy (python3-scipy)"
fi

start=$SECONDS
mkdir -p "$(dirname "$out")"
tmp=$(mktemp -d "$out.tmp.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
scratch=$tmp/.scratch
mkdir -p "$scratch"

# Runs a command with its output to LOG; on failure shows the log's end.
logged() {
  local log=$1
  shift
  if ! "$@" >>"$log" 2>&1; then
    echo "fixtures: failed: $*" >&2
    tail -n 20 "$log" >&2
    exit 1
  fi
}
made() { echo "fixtures: $1 ($(du -sh "$tmp/$1" | cut -f1))${2:+ $2}"; }

# --- pydicom's test RTSTRUCT -------------------------------------------------
if [ "$which" = tests ]; then
  mkdir -p "$tmp/pydicom"
  cp "$pydicom_rtstruct" "$tmp/pydicom/rtstruct.dcm"
  made pydicom/rtstruct.dcm "from $pydicom_rtstruct"
fi

# --- a study from a label volume ---------------------------------------------
# plastimatch's default structure colours, in its order.
colors=("255 0 0" "255 255 0" "255 0 255" "0 255 255" "0 255 0" "0 0 255"
  "255 128 128" "255 255 128" "255 128 255" "128 255 255" "128 255 128"
  "128 128 255" "200 128 128" "200 200 128" "200 128 200" "128 200 200")

# study_from_masks NAME REFERENCE_IMAGE MASK...: the masks (0/1 images on
# the reference's grid, ROI names their file names) as one structure-set
# image (weights 2^N: bit N = mask N, named in ss.txt), then the reference
# as a DICOM series with the RTSTRUCT plastimatch contours from it.
study_from_masks() {
  local name=$1 ref=$2
  shift 2
  local d=$tmp/$name log=$tmp/$name/plastimatch.log masks=("$@") weights=() n=0 m
  : >"$d/ss.txt"
  for m in "${masks[@]}"; do
    weights+=($((1 << n)))
    echo "$n|${colors[n % ${#colors[@]}]}|$(basename "$m" .nrrd)" >>"$d/ss.txt"
    n=$((n + 1))
  done
  if [ ${#masks[@]} -eq 1 ]; then
    logged "$log" plastimatch convert --input "${masks[0]}" \
      --output-type uint32 --output-img "$d/ss.nrrd"
  else
    logged "$log" plastimatch add --weight "${weights[*]}" "${masks[@]}" \
      --output "$scratch/$name-ss-float.nrrd"
    logged "$log" plastimatch convert --input "$scratch/$name-ss-float.nrrd" \
      --output-type uint32 --output-img "$d/ss.nrrd"
  fi
  made "$name/ss.nrrd" "+ ss.txt"

  logged "$log" plastimatch convert --input "$ref" \
    --input-ss-img "$d/ss.nrrd" --input-ss-list "$d/ss.txt" \
    --output-dicom "$d/dicom" --filenames-without-uids \
    --patient-name "DFRECON^$name" --patient-id "dfrecon-$name" \
    --rtss-series-description "dfrecon fixture $name"
  [ -f "$d/dicom/rtss.dcm" ] || die "plastimatch wrote no dicom/rtss.dcm (see $log)"
  ln "$d/dicom/rtss.dcm" "$d/rtstruct.dcm" 2>/dev/null || cp "$d/dicom/rtss.dcm" "$d/rtstruct.dcm"
  local images=("$d"/dicom/image*.dcm)
  made "$name/dicom" "${#images[@]} images + rtss.dcm"
  made "$name/rtstruct.dcm" "= dicom/rtss.dcm"

  if command -v dciodvfy >/dev/null; then
    dciodvfy "$d/rtstruct.dcm" >"$d/dciodvfy.txt" 2>&1 || true
    made "$name/dciodvfy.txt" "$(grep -c '^Error' "$d/dciodvfy.txt" || true) errors, $(grep -c '^Warning' "$d/dciodvfy.txt" || true) warnings"
  fi
}

# make_study NAME LABELS.nii.gz REFERENCE_IMAGE
make_study() {
  local name=$1 labels=$2 ref=$3
  local d=$tmp/$name log=$tmp/$name/plastimatch.log
  mkdir -p "$d/masks"
  cp "$labels" "$d/labels.nii.gz"
  made "$name/labels.nii.gz"

  local lo hi
  read -r lo hi < <(plastimatch stats "$d/labels.nii.gz" |
    awk '/^MIN/ {printf "%d %d\n", $2, $6}')
  if [ "$lo" -lt 0 ] || [ "$hi" -gt 31 ]; then
    die "$labels: labels $lo..$hi, want 0..31 (bits of a uint32)"
  fi

  # One mask per label, named "label_N" (bit N of the structure set).
  local masks=() n
  for n in $(seq "$lo" "$hi"); do
    logged "$log" plastimatch threshold --input "$d/labels.nii.gz" \
      --output "$d/masks/label_$n.nrrd" --range "$n,$n"
    masks+=("$d/masks/label_$n.nrrd")
  done
  made "$name/masks" "${masks[*]##*/}"
  study_from_masks "$name" "$ref" "${masks[@]}"

  "$python" "$here/label_stats.py" "$d/labels.nii.gz" --ss-list "$d/ss.txt" \
    --rtstruct "$d/rtstruct.dcm" -o "$d/labels.json"
  made "$name/labels.json"
}

# reorient_axial IN.nii.gz OUT_HEADER.nhdr: the same voxels, read with
# identity direction cosines and origin $axial_origin, as a detached NRRD.
axial_origin="-127.3,-127.7,-90.1"
reorient_axial() {
  local in=$1 nhdr=$2 base
  base=$(basename "$nhdr" .nhdr)
  logged "$scratch/reorient.log" plastimatch convert --input "$in" \
    --output-img "$scratch/$base-src.nhdr"
  local type sizes spacing
  type=$(sed -n 's/^type: //p' "$scratch/$base-src.nhdr")
  sizes=$(sed -n 's/^sizes: //p' "$scratch/$base-src.nhdr")
  read -r -a spacing < <(plastimatch header "$in" | sed -n 's/^Spacing = //p')
  if [ -z "$type" ] || [ -z "$sizes" ] || [ ${#spacing[@]} -ne 3 ]; then
    die "could not read the geometry of $in"
  fi
  cat >"$nhdr" <<EOF
NRRD0004
type: $type
dimension: 3
space: left-posterior-superior
sizes: $sizes
space directions: (${spacing[0]},0,0) (0,${spacing[1]},0) (0,0,${spacing[2]})
kinds: domain domain domain
endian: little
encoding: raw
space origin: ($axial_origin)
data file: $base-src.raw
EOF
}

# --- the k-means segmentation, as shipped (coronal) --------------------------
if [ "$which" = tests ]; then
  make_study kmeans "$kmeans_labels" "$kmeans_t1"
fi

# --- the same voxels, axial ------------------------------------------------
# Both through NIfTI, so that labels and reference image share its float32
# origin to the last bit.
axial_nifti() {
  reorient_axial "$1" "$scratch/$2-axial.nhdr"
  logged "$scratch/reorient.log" plastimatch convert \
    --input "$scratch/$2-axial.nhdr" --output-img "$scratch/$2-axial.nii.gz"
}
if [ "$which" = tests ]; then
  axial_nifti "$kmeans_labels" labels
  axial_nifti "$kmeans_t1" t1
  make_study kmeans_axial "$scratch/labels-axial.nii.gz" "$scratch/t1-axial.nii.gz"
fi

# --- a head CT's structures: body outline, airway, bone ---------------------
# InVesalius' example head CT at 512 x 512 pixels of 0.48 mm, 1.5 mm apart,
# thresholded as auto-contouring does (scripts/ct_structures.py). Bone has
# up to dozens of contours per plane; the body outline over a thousand
# points per contour, so plastimatch writes some ContourData as VR UN.
if [ "$which" = bench ]; then
  mkdir -p "$tmp/ct_head"
  logged "$tmp/ct_head/ct_structures.log" "$python" "$here/ct_structures.py" "$cranium" \
    "$tmp/ct_head"
  made ct_head/masks "BODY AIRWAY BONE"
  study_from_masks ct_head "$tmp/ct_head/ct.nrrd" "$tmp/ct_head/masks/BODY.nrrd" \
    "$tmp/ct_head/masks/AIRWAY.nrrd" "$tmp/ct_head/masks/BONE.nrrd"
  # The DICOM series and RTSTRUCT hold it all (the images 57 MB, the rest 200).
  rm -rf "$tmp/ct_head/ct.nrrd" "$tmp/ct_head/masks" "$tmp/ct_head/ss.nrrd"
fi

# --- real meshes: CGAL's demo data -------------------------------------------
if [ "$which" = tests ]; then
  cgal_meshes=(femur bunny00 armadillo refined_elephant elephant blobby eight sphere cube knot1)
  mkdir -p "$tmp/meshes"
  members=()
  for m in "${cgal_meshes[@]}"; do members+=("data/meshes/$m.off"); done
  logged "$scratch/meshes.log" tar -xzf "$cgal_data" -C "$tmp/meshes" --strip-components=2 \
    "${members[@]}"
  made meshes "(${#cgal_meshes[@]} OFF files)"
fi

rm -rf "$scratch"
echo "$want_stamp" >"$tmp/.complete"
chmod 755 "$tmp" # mktemp made it 700
if [ -e "$out" ]; then
  old=$(mktemp -d "$out.old.XXXXXX")
  mv "$out" "$old/"
  mv "$tmp" "$out"
  rm -rf "$old"
else
  mv "$tmp" "$out"
fi
trap - EXIT
echo "fixtures: done in $((SECONDS - start)) s: $out"
