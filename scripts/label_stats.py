#!/usr/bin/python3
"""Per-label voxel counts and volumes of a NIfTI-1 label volume, as JSON.

Usage: /usr/bin/python3 scripts/label_stats.py LABELS.nii[.gz] \
           [--ss-list SS.txt] [--rtstruct RTSS.dcm] [-o OUT.json]

An independent reference for dfrecon's RTSTRUCT reader tests
(scripts/fixtures.sh makes the fixtures): the NIfTI-1 header (348 bytes:
dim, datatype, pixdim, vox_offset, xyzt_units) is parsed by hand and the
voxels counted with numpy, so nothing here shares code with ITK, plastimatch
or the C++ reader. Run it with Debian's /usr/bin/python3 (python3-numpy;
python3-pydicom only for --rtstruct).

For every label value present: voxel_count, voxel_volume_mm3 (product of
pixdim[1..3] in mm), volume_cc = voxel_count * voxel_volume_mm3 / 1000, and
edge_voxels: how many of its voxels lie in the first or last row or column
of their slice (slices along the third axis, as plastimatch contours them).
plastimatch leaves the contours of a label with edge voxels open along the
image edge, and where the label covers the edge all round (a background) the
contours, filled, give its complement: compare volumes only where this is 0.

--ss-list: plastimatch's structure list ("bit|r g b|name" per line) for a
structure-set image whose bit N marks label N (scripts/fixtures.sh builds it
so): gives each label its ROI name. --rtstruct: the RT Structure Set that
plastimatch wrote; each label's ROI is looked up there by that name, its ROI
Number and number of contours recorded, and a label whose ROI is missing is
an error.
"""
import argparse
import gzip
import json
import struct
import sys

import numpy as np

# NIfTI-1 datatype codes this script reads (integer label maps, and floats
# holding whole numbers).
DTYPES = {
    2: "u1", 4: "i2", 8: "i4", 16: "f4", 64: "f8",
    256: "i1", 512: "u2", 768: "u4", 1024: "i8", 1280: "u8",
}
# xyzt_units & 7: metres, millimetres, micrometres -> mm factor.
UNIT_TO_MM = {0: 1.0, 1: 1000.0, 2: 1.0, 3: 0.001}


def read_nifti(path):
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rb") as f:
        data = f.read()
    if len(data) < 348:
        sys.exit(f"{path}: {len(data)} bytes, shorter than a NIfTI-1 header")
    for endian in "<>":
        if struct.unpack(endian + "i", data[0:4])[0] == 348:
            break
    else:
        sys.exit(f"{path}: sizeof_hdr is not 348: not NIfTI-1")
    magic = data[344:348]
    if magic not in (b"n+1\0", b"ni1\0"):
        sys.exit(f"{path}: magic {magic!r}: not NIfTI-1")
    if magic == b"ni1\0":
        sys.exit(f"{path}: header-only NIfTI pair (.hdr/.img) not supported")
    dim = struct.unpack(endian + "8h", data[40:56])
    datatype, bitpix = struct.unpack(endian + "2h", data[70:74])
    pixdim = struct.unpack(endian + "8f", data[76:108])
    vox_offset = struct.unpack(endian + "f", data[108:112])[0]
    scl_slope, scl_inter = struct.unpack(endian + "2f", data[112:120])
    xyzt_units = data[123]
    ndim = dim[0]
    if not 1 <= ndim <= 7:
        sys.exit(f"{path}: dim[0] = {ndim}")
    shape = [d for d in dim[1:1 + ndim]]
    if ndim > 3 and any(d != 1 for d in shape[3:]):
        sys.exit(f"{path}: {ndim}-D with more than one volume: {shape}")
    shape = (shape + [1, 1, 1])[:3]
    if datatype not in DTYPES:
        sys.exit(f"{path}: datatype {datatype} not supported")
    dt = np.dtype(endian + DTYPES[datatype])
    if dt.itemsize * 8 != bitpix:
        sys.exit(f"{path}: bitpix {bitpix} does not match datatype {datatype}")
    n = shape[0] * shape[1] * shape[2]
    off = int(vox_offset)
    if off != vox_offset or off < 348:
        sys.exit(f"{path}: vox_offset {vox_offset}")
    if len(data) < off + n * dt.itemsize:
        sys.exit(f"{path}: {len(data)} bytes, need {off + n * dt.itemsize}")
    vox = np.frombuffer(data, dtype=dt, count=n, offset=off)
    if scl_slope not in (0.0, 1.0) or scl_inter != 0.0:
        sys.exit(f"{path}: scl_slope {scl_slope}, scl_inter {scl_inter}: "
                 "a label map should not be scaled")
    if vox.dtype.kind == "f":
        if not np.all(np.isfinite(vox)) or np.any(vox != np.round(vox)):
            sys.exit(f"{path}: float voxels that are not whole numbers")
        vox = vox.astype(np.int64)
    to_mm = UNIT_TO_MM.get(xyzt_units & 7)
    if to_mm is None:
        sys.exit(f"{path}: spatial unit code {xyzt_units & 7}")
    spacing = [abs(pixdim[i]) * to_mm for i in (1, 2, 3)]
    if ndim < 3:
        spacing[ndim:] = [1.0] * (3 - ndim)  # unused axes: one voxel thick
    # NIfTI is x fastest: the array is [z][y][x].
    vox = vox.reshape(shape[2], shape[1], shape[0])
    return dict(dims=shape, datatype=datatype, spacing_mm=spacing,
                vox_offset=off, voxels=vox)


def read_ss_list(path):
    names = {}
    with open(path) as f:
        for line in f:
            line = line.rstrip("\r\n")
            if not line:
                continue
            bit, _color, name = line.split("|", 2)
            names[int(bit)] = name
    return names


def read_rtstruct(path):
    import pydicom  # only for --rtstruct

    ds = pydicom.dcmread(path)
    rois = {}
    for roi in ds.StructureSetROISequence:
        rois[roi.ROIName] = dict(number=int(roi.ROINumber), contours=0)
    by_number = {r["number"]: r for r in rois.values()}
    for rc in ds.ROIContourSequence:
        r = by_number.get(int(rc.ReferencedROINumber))
        if r is not None:
            r["contours"] = len(rc.get("ContourSequence", []))
    return rois


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("nifti")
    ap.add_argument("--ss-list")
    ap.add_argument("--rtstruct")
    ap.add_argument("-o", "--output")
    a = ap.parse_args()

    img = read_nifti(a.nifti)
    vox = img["voxels"]
    if vox.min() < 0:
        sys.exit(f"{a.nifti}: negative labels")
    counts = np.bincount(vox.astype(np.int64).ravel())
    edge = np.zeros(vox.shape, dtype=bool)
    edge[:, [0, -1], :] = True
    edge[:, :, [0, -1]] = True
    edge_counts = np.bincount(vox[edge].astype(np.int64), minlength=counts.size)
    voxel_mm3 = float(np.prod(img["spacing_mm"]))
    names = read_ss_list(a.ss_list) if a.ss_list else {}
    rois = read_rtstruct(a.rtstruct) if a.rtstruct else None

    labels = []
    for value in np.nonzero(counts)[0]:
        value = int(value)
        n = int(counts[value])
        entry = dict(label=value, voxel_count=n, voxel_volume_mm3=voxel_mm3,
                     volume_cc=n * voxel_mm3 / 1000.0,
                     edge_voxels=int(edge_counts[value]))
        if value in names:
            entry["roi_name"] = names[value]
            if rois is not None:
                roi = rois.get(names[value])
                if roi is None:
                    sys.exit(f"{a.rtstruct}: no ROI named {names[value]!r} "
                             f"(label {value})")
                entry["roi_number"] = roi["number"]
                entry["roi_contours"] = roi["contours"]
        labels.append(entry)

    out = dict(
        source=a.nifti.rsplit("/", 1)[-1],
        dims=img["dims"],
        spacing_mm=img["spacing_mm"],
        nifti_datatype=img["datatype"],
        vox_offset=img["vox_offset"],
        voxel_count_total=int(vox.size),
        labels=labels,
    )
    text = json.dumps(out, indent=2) + "\n"
    if a.output:
        with open(a.output, "w") as f:
            f.write(text)
    else:
        sys.stdout.write(text)


if __name__ == "__main__":
    main()
