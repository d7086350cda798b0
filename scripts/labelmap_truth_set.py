#!/usr/bin/env python3
"""A label-map truth set from a truth set (scripts/truth_sets.sh): each true
surface L<label>.ply voxelised at 1 mm (voxel centres inside the surface,
VTK's polydata stencil; where two surfaces claim a voxel the smaller label
keeps it), written as a label volume with its names, and contoured by
`dfrecon convert` as segmentation tools export label maps: pixel-edge
staircases on every voxel plane. The true surfaces and volumes are the
source set's. usage: labelmap_truth_set.py SOURCE_SET OUT_SET DFRECON"""
import os
import shutil
import subprocess
import sys

import numpy as np
import vtk
from vtk.util import numpy_support


def read_ply(path):
    reader = vtk.vtkPLYReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def voxelise(surface, origin, dims, spacing):
    image = vtk.vtkImageData()
    image.SetOrigin(origin)
    image.SetSpacing(spacing, spacing, spacing)
    image.SetDimensions(dims)
    image.AllocateScalars(vtk.VTK_UNSIGNED_CHAR, 1)
    image.GetPointData().GetScalars().Fill(1)
    stencil = vtk.vtkPolyDataToImageStencil()
    stencil.SetInputData(surface)
    stencil.SetOutputOrigin(origin)
    stencil.SetOutputSpacing(spacing, spacing, spacing)
    stencil.SetOutputWholeExtent(image.GetExtent())
    stencil.Update()
    cut = vtk.vtkImageStencil()
    cut.SetInputData(image)
    cut.SetStencilConnection(stencil.GetOutputPort())
    cut.ReverseStencilOff()
    cut.SetBackgroundValue(0)
    cut.Update()
    values = numpy_support.vtk_to_numpy(cut.GetOutput().GetPointData().GetScalars())
    return values.reshape(dims[2], dims[1], dims[0]) > 0


def main():
    source, out, dfrecon = sys.argv[1:4]
    spacing = 1.0
    names = sorted((f for f in os.listdir(source) if f.startswith("L") and f.endswith(".ply")),
                   key=lambda f: int(f[1:-4]))
    surfaces = {int(f[1:-4]): read_ply(os.path.join(source, f)) for f in names}
    lo = np.min([s.GetBounds()[0::2] for s in surfaces.values()], axis=0) - 2
    hi = np.max([s.GetBounds()[1::2] for s in surfaces.values()], axis=0) + 2
    # Voxel centres off the source's planes and off whole millimetres.
    origin = tuple(np.floor(lo) + 0.31)
    dims = tuple(int(np.ceil((h - o) / spacing)) + 1 for h, o in zip(hi, origin))
    labels = np.zeros((dims[2], dims[1], dims[0]), dtype=np.uint16)
    for label in sorted(surfaces):
        inside = voxelise(surfaces[label], origin, dims, spacing)
        labels[inside & (labels == 0)] = label
    tmp = out + ".tmp"
    shutil.rmtree(tmp, ignore_errors=True)
    os.makedirs(tmp)
    volume = os.path.join(tmp, "labels.nrrd")
    with open(volume, "wb") as f:
        f.write(("NRRD0004\ntype: uint16\ndimension: 3\nspace: left-posterior-superior\n"
                 "sizes: %d %d %d\nspace directions: (%g,0,0) (0,%g,0) (0,0,%g)\n"
                 "space origin: (%g,%g,%g)\nendian: little\nencoding: raw\n\n"
                 % (dims + (spacing,) * 3 + origin)).encode())
        f.write(labels.astype("<u2").tobytes(order="C"))
    with open(os.path.join(tmp, "labels.txt"), "w") as f:
        for label in sorted(surfaces):
            f.write("%d L%d\n" % (label, label))
    subprocess.run([dfrecon, "-q", "convert", volume, "-o", os.path.join(tmp, "set-rtstruct.dcm")],
                   check=True)
    for f in names + ["set-surface-cc.txt"]:
        shutil.copy(os.path.join(source, f), tmp)
    os.remove(volume)
    shutil.rmtree(out, ignore_errors=True)
    os.rename(tmp, out)


if __name__ == "__main__":
    main()
