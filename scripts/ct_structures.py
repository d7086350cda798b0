#!/usr/bin/env python3
"""Head CT structures from Debian's invesalius-examples, as masks to contour.

InVesalius' example project (Cranium.inv3, a gzipped tar) holds a head CT:
matrix.dat, int16 Hounsfield units, 108 axial slices of 256 x 256 pixels,
0.957 x 0.957 x 1.5 mm. This script resamples each slice to 512 x 512 pixels
of half the size (bilinear), as a planning CT of the head has them, and
thresholds the structures a planning system's auto-contouring makes:

  BODY    the external outline: the largest 3D component above -400 HU,
          holes filled slice by slice (one contour per plane, up to a couple
          of thousand points);
  AIRWAY  air below -400 HU inside BODY, components of 50 voxels or more
          (nasal cavity, sinuses, pharynx: many small contours);
  BONE    InVesalius' bone threshold, 226 HU and above, components of
          10 voxels or more (skull, vertebrae, teeth: up to dozens of
          contours per plane, with holes).

Writes OUTDIR/ct.nrrd (int16 HU, the reference image for plastimatch's DICOM
export) and OUTDIR/masks/{BODY,AIRWAY,BONE}.nrrd (uint8 0/1), identity
direction cosines, origin at the first voxel's centre. Deterministic.

Usage: ct_structures.py CRANIUM.inv3 OUTDIR
"""
import io
import plistlib
import sys
import tarfile
from pathlib import Path

import numpy as np
from scipy import ndimage


def read_inv3(path):
    """The CT volume (z, y, x) and its spacing (x, y, z), in mm."""
    with tarfile.open(path, "r:gz") as tar:
        members = {Path(m.name).name: m for m in tar.getmembers() if m.isfile()}
        main = plistlib.load(tar.extractfile(members["main.plist"]))
        matrix = main["matrix"]
        if matrix["dtype"] != "int16":
            raise SystemExit(f"{path}: matrix dtype {matrix['dtype']}, want int16")
        raw = tar.extractfile(members[matrix["filename"]]).read()
    shape = tuple(matrix["shape"])
    volume = np.frombuffer(raw, dtype="<i2")
    if volume.size != np.prod(shape):
        raise SystemExit(f"{path}: {volume.size} voxels, header says {shape}")
    return volume.reshape(shape), [float(s) for s in main["spacing"]]


def upsample_in_plane(volume):
    """Each slice at twice the pixels a side, bilinear between pixel centres."""
    zoomed = ndimage.zoom(volume.astype(np.float32), (1, 2, 2), order=1, mode="nearest",
                          grid_mode=True)
    return np.rint(zoomed).astype(np.int16)


def large_components(mask, min_voxels):
    labels, count = ndimage.label(mask)
    if count == 0:
        return mask
    sizes = np.bincount(labels.ravel())
    keep = sizes >= min_voxels
    keep[0] = False
    return keep[labels]


def body_of(hu):
    labels, count = ndimage.label(hu > -400)
    if count == 0:
        raise SystemExit("no voxel above -400 HU")
    sizes = np.bincount(labels.ravel())
    sizes[0] = 0
    body = labels == int(np.argmax(sizes))
    return np.stack([ndimage.binary_fill_holes(s) for s in body])


def write_nrrd(path, volume, spacing, origin):
    """Volume (z, y, x) as a raw little-endian NRRD, LPS, identity axes."""
    types = {np.dtype("int16"): "int16", np.dtype("uint8"): "uint8"}
    header = (
        "NRRD0004\n"
        f"type: {types[volume.dtype]}\n"
        "dimension: 3\n"
        "space: left-posterior-superior\n"
        f"sizes: {volume.shape[2]} {volume.shape[1]} {volume.shape[0]}\n"
        f"space directions: ({spacing[0]!r},0,0) (0,{spacing[1]!r},0) (0,0,{spacing[2]!r})\n"
        "kinds: domain domain domain\n"
        "endian: little\n"
        "encoding: raw\n"
        f"space origin: ({origin[0]!r},{origin[1]!r},{origin[2]!r})\n\n")
    buffer = io.BytesIO()
    buffer.write(header.encode("ascii"))
    buffer.write(np.ascontiguousarray(volume).astype(volume.dtype.newbyteorder("<")).tobytes())
    tmp = path.with_suffix(".tmp")
    tmp.write_bytes(buffer.getvalue())
    tmp.replace(path)


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    source, out = Path(argv[1]), Path(argv[2])
    volume, spacing = read_inv3(source)
    hu = upsample_in_plane(volume)
    spacing = [spacing[0] / 2, spacing[1] / 2, spacing[2]]
    # Centred in x and y, the first plane at z = 0.
    origin = [-0.5 * (hu.shape[2] - 1) * spacing[0], -0.5 * (hu.shape[1] - 1) * spacing[1], 0.0]
    body = body_of(hu)
    structures = {
        "BODY": body,
        "AIRWAY": large_components(body & (hu < -400), 50),
        "BONE": large_components(hu >= 226, 10),
    }
    (out / "masks").mkdir(parents=True, exist_ok=True)
    write_nrrd(out / "ct.nrrd", hu, spacing, origin)
    for name, mask in structures.items():
        write_nrrd(out / "masks" / f"{name}.nrrd", mask.astype(np.uint8), spacing, origin)
        print(f"{name}: {int(mask.sum())} voxels")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
