#!/usr/bin/python3
"""Ground truth for reconstruction from contours on real anatomy: contours the way a treatment planning system or a
smoothed AI segmentation writes them (smooth polygons, points on no pixel grid), cut from surfaces that are known.

From an atlas label volume (default: Debian mricron-data's brodmann.nii.gz; any label NIfTI works): about --labels
labels picked by label number (every k-th of those with >= --min-voxels voxels) and --extra more, those richest in
holes and branching. Each is meshed (vtkDiscreteFlyingEdges3D), smoothed (vtkWindowedSincPolyDataFilter: 20
iterations, pass band 0.05) -- that closed smooth surface is the TRUTH -- and cut by parallel planes --gap mm apart,
the first --offset mm above the volume's minimum along the normal (--axis z axial, y coronal, x sagittal). Only closed
loops are kept; each is resampled to points --step mm apart and dropped when it then self-intersects, encloses under
--min-area mm^2 or crosses another loop of its ROI (drops counted on stderr). ROIs on one plane only are left out.

Frame: DICOM patient LPS of the atlas (NIfTI sform, else qform, to RAS; x and y negated). Patient/study/frame modules
come from --template. ROI numbers are the label numbers, names 'L<label>'.

usage: truth_set.py [--atlas NII] [--axis z|y|x] [--gap MM] [--offset MM] [--surfaces DIR] OUT_PREFIX
  -> OUT_PREFIX-rtstruct.dcm, OUT_PREFIX-surface-cc.txt (each true surface's volume, cc) and, with --surfaces,
     DIR/L<label>.ply (the true surfaces, binary PLY, patient LPS mm).
Needs python3 with vtk (Debian python3-vtk9), numpy and pydicom; atlases: apt-get install mricron-data."""
import argparse, colorsys, datetime, math, os, sys, time
import numpy as np
import pydicom
import vtk
from pydicom.dataset import Dataset
from pydicom.sequence import Sequence
from pydicom.uid import generate_uid
from vtk.util import numpy_support as ns

here = os.path.dirname(os.path.abspath(__file__))


def parse(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--atlas", default="/usr/share/mricron/templates/brodmann.nii.gz")
    ap.add_argument("--axis", choices=["z", "x", "y"], default="z")
    ap.add_argument("--surfaces", help="write each true surface here as L<label>.ply (binary, patient LPS mm)")
    ap.add_argument("--labels", type=int, default=30, help="about this many labels by label number")
    ap.add_argument("--extra", type=int, default=6, help="and this many with the most holes and branching")
    ap.add_argument("--min-voxels", type=int, default=300)
    ap.add_argument("--gap", type=float, default=2.5)
    ap.add_argument("--offset", type=float, default=0.37)
    ap.add_argument("--step", type=float, default=1.0)
    ap.add_argument("--min-area", type=float, default=2.0)
    ap.add_argument("--template", default=f"{here}/../tests/data/fuzz-rtstruct/squares.dcm")
    return ap.parse_args(argv)


def init(args):
    """load the atlas and set the module state surface() and loops() use (importers: init(parse(["unused"])), then
    surface(label) is the true closed surface of that label, as the structure sets were cut from)"""
    global a, AX, INPLANE, lab, spacing, origin, to_lps, plane_sets, counts, usable, k, chosen, xf
    a = args
    vtk.vtkObject.GlobalWarningDisplayOff()
    AX = "xyz".index(a.axis); INPLANE = [i for i in range(3) if i != AX]

    # --- atlas and its patient (LPS) frame
    rd = vtk.vtkNIFTIImageReader(); rd.SetFileName(a.atlas); rd.Update()
    img = rd.GetOutput(); nx, ny, nz = img.GetDimensions()
    spacing, origin = np.array(img.GetSpacing()), np.array(img.GetOrigin())
    lab = ns.vtk_to_numpy(img.GetPointData().GetScalars()).reshape(nz, ny, nx)
    hdr = rd.GetNIFTIHeader()
    m = rd.GetSFormMatrix() if hdr.GetSFormCode() > 0 else rd.GetQFormMatrix() if hdr.GetQFormCode() > 0 else None
    ras = np.eye(4) if m is None else np.array([[m.GetElement(r, c) for c in range(4)] for r in range(4)])
    to_lps = np.diag([-1.0, -1.0, 1.0, 1.0]) @ ras          # VTK image coordinates -> patient LPS
    corners = np.array([[i, j, k, 1] for i in (0, nx - 1) for j in (0, ny - 1) for k in (0, nz - 1)], float)
    corners[:, :3] = corners[:, :3] * spacing + origin
    lo, hi = (to_lps @ corners.T)[:3].min(1), (to_lps @ corners.T)[:3].max(1)
    plane_sets = [lo[i] + a.offset + a.gap * np.arange(int((hi[i] - lo[i] - a.offset) // a.gap) + 1)
                  for i in range(3)]

    counts = np.bincount(lab.ravel())
    usable = [l for l in range(1, len(counts)) if counts[l] >= a.min_voxels]
    k = max(1, math.ceil(len(usable) / a.labels))
    chosen = usable[::k]
    xf = vtk.vtkTransform(); mat = vtk.vtkMatrix4x4()
    for r in range(4):
        for c in range(4):
            mat.SetElement(r, c, to_lps[r, c])
    xf.SetMatrix(mat)


def surface(label):
    """closed smoothed surface of one label, in patient LPS"""
    kk, jj, ii = np.nonzero(lab == label)
    k0, j0, i0 = kk.min(), jj.min(), ii.min()
    sub = np.pad(lab[k0:kk.max() + 1, j0:jj.max() + 1, i0:ii.max() + 1] == label, 2).astype(np.uint8)
    im = vtk.vtkImageData(); im.SetDimensions(sub.shape[2], sub.shape[1], sub.shape[0])
    im.SetSpacing(*spacing); im.SetOrigin(*(origin + (np.array([i0, j0, k0]) - 2) * spacing))
    im.GetPointData().SetScalars(ns.numpy_to_vtk(sub.ravel(), deep=1))
    fe = vtk.vtkDiscreteFlyingEdges3D(); fe.SetInputData(im); fe.SetValue(0, 1)
    fe.ComputeNormalsOff(); fe.ComputeGradientsOff(); fe.ComputeScalarsOff()
    sm = vtk.vtkWindowedSincPolyDataFilter(); sm.SetInputConnection(fe.GetOutputPort())
    sm.SetNumberOfIterations(20); sm.SetPassBand(0.05); sm.NonManifoldSmoothingOff(); sm.FeatureEdgeSmoothingOff()
    sm.BoundarySmoothingOff(); sm.NormalizeCoordinatesOn()
    tp = vtk.vtkTransformPolyDataFilter(); tp.SetInputConnection(sm.GetOutputPort()); tp.SetTransform(xf)
    tp.SetOutputPointsPrecision(vtk.vtkAlgorithm.DOUBLE_PRECISION); tp.Update()
    return tp.GetOutput()


def seg_cross(a0, a1, b0, b1):
    """n x m matrix: segment i of (a0->a1) meets segment j of (b0->b1) (touching and collinear overlap count)"""
    def orient(p, q, r):
        return (q[..., 0] - p[..., 0]) * (r[..., 1] - p[..., 1]) - (q[..., 1] - p[..., 1]) * (r[..., 0] - p[..., 0])
    A0, A1, B0, B1 = a0[:, None], a1[:, None], b0[None], b1[None]
    o1, o2, o3, o4 = orient(A0, A1, B0), orient(A0, A1, B1), orient(B0, B1, A0), orient(B0, B1, A1)
    box = ((np.minimum(A0[..., 0], A1[..., 0]) <= np.maximum(B0[..., 0], B1[..., 0])) &
           (np.minimum(B0[..., 0], B1[..., 0]) <= np.maximum(A0[..., 0], A1[..., 0])) &
           (np.minimum(A0[..., 1], A1[..., 1]) <= np.maximum(B0[..., 1], B1[..., 1])) &
           (np.minimum(B0[..., 1], B1[..., 1]) <= np.maximum(A0[..., 1], A1[..., 1])))
    return (o1 * o2 <= 0) & (o3 * o4 <= 0) & box


def self_intersects(p):
    n = len(p); x = seg_cross(p, np.roll(p, -1, 0), p, np.roll(p, -1, 0))
    i, j = np.triu_indices(n, 2)
    keep = ~((i == 0) & (j == n - 1))                    # first and last segments are adjacent too
    return bool(x[i[keep], j[keep]].any())


def area(p):
    return 0.5 * abs(np.dot(p[:, 0], np.roll(p[:, 1], -1)) - np.dot(p[:, 1], np.roll(p[:, 0], -1)))


def resample(q, step):
    """closed polyline (no repeated end point) -> points `step` apart along its length, at least 8"""
    d = np.linalg.norm(np.diff(q, axis=0, append=q[:1]), axis=1)
    q, d = q[d > 1e-9], d[d > 1e-9]
    s = np.concatenate([[0.0], np.cumsum(d)]); L = s[-1]
    n = max(8, int(round(L / step)))
    t = np.arange(n) * (L / n); qq = np.vstack([q, q[:1]])
    return np.column_stack([np.interp(t, s, qq[:, 0]), np.interp(t, s, qq[:, 1])])


def fmt(v):
    s = f"{v:.4f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def inside(pt, poly):
    x, y = pt; xs, ys = poly[:, 0], poly[:, 1]; xs2, ys2 = np.roll(xs, -1), np.roll(ys, -1)
    c = (ys > y) != (ys2 > y)
    xi = xs + (y - ys) * (xs2 - xs) / np.where(ys2 == ys, 1e-300, ys2 - ys)
    return bool(np.count_nonzero(c & (x < xi)) % 2)


def loops(surf, ax, drops):
    """cut a closed surface by the planes normal to axis `ax`: {plane: [resampled loops (n x 2, in-plane)]}"""
    inpl = [i for i in range(3) if i != ax]; planes = plane_sets[ax]
    b = surf.GetBounds(); vals = [v for v in planes if b[2 * ax] < v < b[2 * ax + 1]]
    pl = vtk.vtkPlane(); pl.SetOrigin(0, 0, 0); nrm = [0, 0, 0]; nrm[ax] = 1; pl.SetNormal(*nrm)
    cut = vtk.vtkCutter(); cut.SetCutFunction(pl); cut.SetInputData(surf)
    for i, v in enumerate(vals):
        cut.SetValue(i, v)
    st = vtk.vtkStripper(); st.SetInputConnection(cut.GetOutputPort()); st.JoinContiguousSegmentsOn(); st.Update()
    out = st.GetOutput(); byplane = {}
    if not out.GetNumberOfPoints():
        return byplane
    P = ns.vtk_to_numpy(out.GetPoints().GetData())
    lines = out.GetLines(); lines.InitTraversal(); ids = vtk.vtkIdList()
    while lines.GetNextCell(ids):
        idl = [ids.GetId(i) for i in range(ids.GetNumberOfIds())]
        if len(idl) < 4 or idl[0] != idl[-1]:
            drops["open"] += 1; continue
        xyz = P[idl[:-1]].astype(float)
        v = planes[int(np.argmin(np.abs(planes - xyz[:, ax].mean())))]
        q = np.round(resample(xyz[:, inpl], a.step), 4)
        if self_intersects(q):
            drops["self_intersecting"] += 1; continue
        if area(q) < a.min_area:
            drops["small"] += 1; continue
        byplane.setdefault(v, []).append(q)
    for v in byplane:
        kept = []
        for q in sorted(byplane[v], key=area, reverse=True):   # a loop crossing a bigger one of this plane goes
            lo_q, hi_q = q.min(0), q.max(0)
            if any((lo_q <= r.max(0)).all() and (r.min(0) <= hi_q).all() and
                   seg_cross(q, np.roll(q, -1, 0), r, np.roll(r, -1, 0)).any() for r in kept):
                drops["crossing"] += 1; continue
            kept.append(q)
        byplane[v] = kept
    return byplane


def main(argv=None):
    global chosen
    t0 = time.time()
    init(parse(argv))
    print(f"{os.path.basename(a.atlas)}: {len(usable)} labels >= {a.min_voxels} voxels, every {k}th: {len(chosen)}",
          file=sys.stderr)
    # extras: the labels richest in holes and branching on axial planes (whatever --axis is, so that the axial and
    # sagittal sets hold the same labels): score = loops nested in another + (most loops on one plane - 1)
    if a.extra:
        score = []
        for label in usable:
            if label in chosen:
                continue
            bp = loops(surface(label), 2, dict(open=0, self_intersecting=0, small=0, crossing=0))
            nested = sum(sum(any(inside(p[0], q) for j, q in enumerate(v) if j != i) for i, p in enumerate(v))
                         for v in bp.values())
            score.append((-(nested + max(map(len, bp.values()), default=1) - 1), label))
        extra = sorted(l for _, l in sorted(score)[:a.extra])
        print(f"extra labels (holes, branching): {extra}", file=sys.stderr)
        chosen = sorted(chosen + extra)

    drops = dict(open=0, self_intersecting=0, small=0, crossing=0)
    rois, vols = [], []
    for label in chosen:
        surf = surface(label)
        mp = vtk.vtkMassProperties(); mp.SetInputData(surf); mp.Update(); vols.append((label, mp.GetVolume() / 1000))
        if a.surfaces:
            os.makedirs(a.surfaces, exist_ok=True)
            w = vtk.vtkPLYWriter(); w.SetFileName(os.path.join(a.surfaces, f"L{label}.ply")); w.SetInputData(surf)
            w.SetFileTypeToBinary(); w.Write()
        bp = loops(surf, AX, drops)
        contours = []
        for v in sorted(bp):
            for q in bp[v]:
                xyz = np.empty((len(q), 3)); xyz[:, INPLANE] = q; xyz[:, AX] = v
                contours.append((v, xyz))
        if len(bp) >= 2:
            rois.append((label, contours))
        elif bp:
            drops["roi_on_one_plane"] = drops.get("roi_on_one_plane", 0) + 1   # no plane spacing, no volume: left out

    # --- RT Structure Set
    ds = pydicom.dcmread(a.template)
    now = datetime.datetime.now()
    ds.SOPInstanceUID = generate_uid(); ds.file_meta.MediaStorageSOPInstanceUID = ds.SOPInstanceUID
    ds.SeriesInstanceUID = generate_uid()
    for kw in ("InstanceCreatorUID",):
        if kw in ds:
            delattr(ds, kw)
    ds.InstanceCreationDate = ds.StructureSetDate = now.strftime("%Y%m%d")
    ds.InstanceCreationTime = ds.StructureSetTime = now.strftime("%H%M%S")
    ds.Manufacturer = "truth_set"; ds.ManufacturerModelName = "truth_set.py"; ds.SoftwareVersions = "1"
    ds.file_meta.ImplementationClassUID = pydicom.uid.PYDICOM_IMPLEMENTATION_UID
    ds.file_meta.ImplementationVersionName = "PYDICOM " + pydicom.__version__
    ds.SeriesDescription = f"smoothed {os.path.basename(a.atlas).split('.')[0]} contours, {a.axis} planes {a.gap} mm"
    ds.StructureSetLabel = ds.StructureSetName = "TRUTH_" + a.axis.upper()
    for_uid = ds.ReferencedFrameOfReferenceSequence[0].FrameOfReferenceUID
    ssroi, roic, obs = Sequence(), Sequence(), Sequence()
    for n, (label, contours) in enumerate(rois):
        r = Dataset(); r.ROINumber = label; r.ReferencedFrameOfReferenceUID = for_uid; r.ROIName = f"L{label}"
        r.ROIGenerationAlgorithm = "AUTOMATIC"; ssroi.append(r)
        c = Dataset(); c.ReferencedROINumber = label
        c.ROIDisplayColor = [int(round(255 * x)) for x in colorsys.hsv_to_rgb((label * 0.618034) % 1, 0.7, 0.95)]
        cs = Sequence()
        for v, xyz in contours:
            it = Dataset(); it.ContourGeometricType = "CLOSED_PLANAR"; it.NumberOfContourPoints = len(xyz)
            it.ContourData = [fmt(x) for x in xyz.ravel()]
            cs.append(it)
        c.ContourSequence = cs; roic.append(c)
        o = Dataset(); o.ObservationNumber = n + 1; o.ReferencedROINumber = label; o.ROIObservationLabel = f"L{label}"
        o.RTROIInterpretedType = "ORGAN"; o.ROIInterpreter = ""; obs.append(o)
    ds.StructureSetROISequence, ds.ROIContourSequence, ds.RTROIObservationsSequence = ssroi, roic, obs
    ds.save_as(f"{a.out}-rtstruct.dcm", write_like_original=False)
    with open(f"{a.out}-surface-cc.txt", "w") as f:
        for label, v in vols:
            if any(label == r[0] for r in rois):
                f.write(f"L{label} {round(v, 4)}\n")

    # --- read back and summarise
    chk = pydicom.dcmread(f"{a.out}-rtstruct.dcm")
    ncont = sum(len(rc.ContourSequence) for rc in chk.ROIContourSequence)
    assert ncont == sum(len(c) for _, c in rois) and len(chk.StructureSetROISequence) == len(rois)
    for rc in chk.ROIContourSequence:
        for c in rc.ContourSequence:
            p = np.array(c.ContourData, float).reshape(-1, 3)
            assert len(p) == c.NumberOfContourPoints and np.ptp(p[:, AX]) == 0
    sizes = sorted(int(counts[l]) for l, _ in rois)
    print(f"{len(rois)} ROIs (voxels {sizes[0]}..{sizes[-1]}), {ncont} contours, dropped {drops}, "
          f"{time.time() - t0:.1f} s", file=sys.stderr)


if __name__ == "__main__":
    main()
