"""dfrecon: watertight, error-bounded surfaces from planar contours.

Contours in (RTSTRUCT, .slices, label volumes, mask stacks, or NumPy arrays),
closed triangle surfaces out as NumPy arrays, with exact distance fields,
error-bounded simplification, surface distance maps and comparisons. The
same C++ library as the ``dfrecon`` program, so the numbers are the same as
its ``--json`` reports. See docs/python.md.

    >>> import dfrecon
    >>> rs = dfrecon.read_contours("RS.dcm")
    >>> mesh = dfrecon.reconstruct(rs, roi="PTV")
    >>> mesh.volume_cc, mesh.vertices.shape, mesh.faces.shape
"""

import os as _os
import sys as _sys

# NumPy from Debian's package where this interpreter has none of its own: the
# module is built against Debian's python3 (make setup installs NumPy for
# it), and another CPython of the same minor version (a pyenv build) can use
# the same NumPy. Appended, so an interpreter's own NumPy always wins.
try:
    import numpy as _np
except ImportError:  # pragma: no cover - depends on the interpreter
    _debian = "/usr/lib/python3/dist-packages"
    _tag = "cpython-%d%d" % _sys.version_info[:2]
    _core = _os.path.join(_debian, "numpy", "core")
    if _os.path.isdir(_core) and any(_tag in f for f in _os.listdir(_core)):
        _sys.path.append(_debian)
    import numpy as _np

try:
    from . import _dfrecon as _core_module
except ImportError as _error:  # the package folder without its extension
    raise ImportError(
        "dfrecon's compiled extension (_dfrecon) is not in %s: build it with "
        "`make build` and put build/python on PYTHONPATH, or install the package "
        "with `pip install .` from the source tree (docs/python.md)"
        % _os.path.dirname(_os.path.abspath(__file__))
    ) from _error
from ._dfrecon import DeviceError, InputError, InvalidResultError

__version__ = _core_module.__version__

__all__ = [
    "__version__",
    "InputError",
    "InvalidResultError",
    "DeviceError",
    "Roi",
    "StructureSet",
    "Mesh",
    "read_contours",
    "read_mesh",
    "reconstruct",
    "margin",
    "combine",
    "histogram",
    "rasterize",
    "slice_fields",
    "distance_field",
    "simplify",
    "surface_distance_maps",
    "compare",
    "compare_sets",
    "segment",
    "geodesic",
    "check",
    "set_device",
    "device_name",
]

InputError.__doc__ = (
    "Bad input (a file, its line or tag, or an array): a ValueError whose "
    "message names the file and what is wrong, as the program's exit code 2; "
    "``file`` and ``line`` (0 where none applies) say where."
)
InvalidResultError.__doc__ = "A result that is not a valid closed solid where one is needed."
DeviceError.__doc__ = "The OpenCL device failed or none matches the device asked for."


def set_device(spec):
    """Use the OpenCL device `spec` (as the program's --device: 'cpu', 'gpu',
    an index or a name part) from now on. The default is $DFRECON_DEVICE, else
    PoCL's CPU device."""
    _core_module._set_device(str(spec))


def device_name():
    """The name of the OpenCL device computations run on."""
    return _core_module._device_name()


# ---- contours ----------------------------------------------------------------


class Roi:
    """One structure of a structure set.

    Attributes: ``name`` (str), ``number`` (DICOM ROI Number or None),
    ``colour`` ((r, g, b) 0-255 or None), ``interpreted_type`` (str or None, DICOM
    RTROIInterpretedType; None where the file gives none), ``planes`` (float64 array: each plane's
    position along the stack's normal, mm), ``contours`` (list of (n, 3)
    float64 arrays, one closed contour each, patient mm), ``orientation``
    ('axial', 'sagittal', 'coronal' or 'oblique'), ``contour_volume_cc``
    (the planning system's sum of area x thickness), ``defect`` (why its
    contours cannot be used, or None), ``contour_reading`` (dict: what
    reading changed, as ``reconstruct --json``'s ``contourReading``),
    ``warnings`` (list of str: the reading's warnings about this ROI; the
    structure set's ``warnings`` hold every one).
    """

    __slots__ = ("name", "number", "colour", "interpreted_type", "planes", "contours",
                 "orientation", "contour_volume_cc", "defect", "contour_reading", "warnings")

    def __init__(self, d):
        for key in self.__slots__:
            setattr(self, key, d[key])

    def __repr__(self):
        return "Roi(%r, number=%r, %d planes, %d contours)" % (
            self.name, self.number, len(self.planes), len(self.contours))


class StructureSet:
    """ROIs of contours, as read by :func:`read_contours` or built by
    :meth:`from_contours`. ``rois`` lists them in file order; index by name or
    DICOM number: ``ss["PTV"]``, ``ss[3]``."""

    def __init__(self, core):
        self._core = core
        self.rois = [Roi(d) for d in core._rois()]

    @classmethod
    def from_contours(cls, rois, colours=None):
        """A structure set from NumPy arrays: ``{"NAME": [array (n, 3), ...]}``,
        each array one closed contour on one axial plane (constant z), in
        patient mm. Contours are read exactly as a .slices file's are (as
        planning systems read them: folds, duplicates and contours of no area
        dropped, crossings resolved by the even-odd rule, each ROI's changes
        in ``Roi.contour_reading``); ``colours`` maps names to (r, g, b)."""
        if not isinstance(rois, dict):
            raise TypeError("from_contours: expected a dict of ROI name -> list of (n, 3) arrays")
        return cls(_core_module._from_contours(rois, dict(colours or {})))

    @property
    def format(self):
        """The input's format as ``dfrecon info`` names it (e.g. 'DICOM RTSTRUCT')."""
        return self._core.format

    @property
    def source(self):
        return self._core.source

    @property
    def warnings(self):
        """The repairs made while reading, as the program prints them."""
        return self._core.warnings

    @property
    def names(self):
        return [r.name for r in self.rois]

    def __len__(self):
        return len(self.rois)

    def __iter__(self):
        return iter(self.rois)

    def __getitem__(self, key):
        for r in self.rois:
            if (isinstance(key, str) and r.name == key) or (
                    isinstance(key, int) and not isinstance(key, bool) and r.number == key):
                return r
        raise KeyError(key)

    def __contains__(self, key):
        try:
            self[key]
            return True
        except KeyError:
            return False

    def write_slices(self, path):
        """Writes the contours as a .slices file (exact: every number reads back the same)."""
        self._core._write_slices(_os.fspath(path))

    def write(self, path, *, like=None):
        """Writes the set to `path`: a DICOM RT Structure Set for ``.dcm``
        (what ``dfrecon convert``/``margin`` write), else a ``.slices`` file.
        An RTSTRUCT refers to the images of `like` (a CT series folder or
        another RTSTRUCT), else, where the set was read from an RTSTRUCT, to
        that file's study, frame of reference and series, so it goes back to
        the planning system on the same images. ROIs without a colour get
        one no other ROI of the set has. Written atomically."""
        path = _os.fspath(path)
        if path.lower().endswith(".dcm"):
            self._core._write_rtstruct(path, _os.fspath(like) if like is not None else "")
        elif like is not None:
            raise ValueError("write(): like= is for DICOM output (.dcm)")
        else:
            self._core._write_slices(path)

    def __repr__(self):
        return "StructureSet(%s, %d ROIs: %s)" % (
            self.format, len(self.rois), ", ".join(self.names))


def read_contours(path, *, label_table=None, accept_intensity=False):
    """Reads contours from `path`: a DICOM RT Structure Set, a .slices file, a
    label volume (.nii, .nii.gz, .nrrd, .nhdr, .seg.nrrd) or a mask stack
    (folder or .json), the format found by content first, then by name.
    Returns a :class:`StructureSet`. Raises :class:`InputError` (a ValueError)
    naming the file for bad input. Contours are read as planning systems read
    them (docs/formats.md, "How contours are read")."""
    return StructureSet(_core_module._read_contours(
        _os.fspath(path), _os.fspath(label_table) if label_table else "",
        bool(accept_intensity)))


def _algebra_settings(step_mm, min_area_mm2, colour, roi_type):
    """What margin() and combine() pass to the module besides their ROIs."""
    return {"step_mm": float(step_mm), "min_area_mm2": float(min_area_mm2),
            "colour": colour, "roi_type": roi_type or ""}


def margin(src, roi, mm, *, name=None, step_mm=0.25, min_area_mm2=1e-4, colour=None,
           roi_type=None):
    """ROI `roi` of `src` grown (``mm`` > 0) or shrunk (< 0) by an exact 3D
    margin, as ``dfrecon margin`` computes it: ``mm`` one number, or six
    (R, L, A, P, S, I) for a margin per patient direction (all of one sign;
    at most 200 mm). Returns ``(StructureSet, report)``: `src`'s ROIs with
    the new one last (named `name`, default ``ROI+MM``/``ROI-MM``; its type
    `roi_type`, default the source's), and a dict with its contour and
    surface volumes, planes and validity. ``step_mm`` and ``min_area_mm2``
    are the program's ``--step`` and ``--min-area``. Write the set with
    :meth:`StructureSet.write`."""
    ss = _structure_set(src)
    values = [float(mm)] if isinstance(mm, (int, float)) else [float(v) for v in mm]
    core, report = _core_module._margin(
        ss._core, _roi_key(roi), values, name or "",
        _algebra_settings(step_mm, min_area_mm2, colour, roi_type))
    return StructureSet(core), report


def combine(src, definition, *, step_mm=0.25, min_area_mm2=1e-4, colour=None, roi_type=None):
    """A new ROI from an expression of `src`'s ROIs, as ``dfrecon combine
    --expr``: ``"Ring = (PTV + 20) - (PTV + 3)"`` (``|``/``+`` union, ``&``
    intersection, ``-`` difference, ``^`` exclusive or, ``ROI + 5`` a margin;
    docs/cli.md). Returns ``(StructureSet, report)`` as :func:`margin`; the
    new ROI's type defaults to CONTROL. An expression that does not parse
    raises ValueError with its column."""
    ss = _structure_set(src)
    core, report = _core_module._combine(
        ss._core, str(definition), _algebra_settings(step_mm, min_area_mm2, colour, roi_type))
    return StructureSet(core), report


def rasterize(src, roi=None, *, voxel_mm=1.0, **options):
    """The voxels inside ROI `roi`'s reconstructed surface, as ``dfrecon
    rasterize --roi ROI --voxel-mm MM`` finds them (the default ``--inside
    surface``: exact ray parity against the same surface ``reconstruct``
    makes with ``options``, its keywords): a dict with ``values``, a bool
    array of shape (nz, ny, nx), and, in the array's own axis order (z, y,
    x), ``spacing`` (mm per index step) and ``directions`` (the LPS unit
    vector of each array axis); ``origin`` is the LPS position (x, y, z) of
    the centre of voxel [0, 0, 0]; ``voxels``, ``volume_cc`` and the
    surface's ``surface_volume_cc``. The grid is the program's for that
    ROI: ``voxel_mm`` cubes around it with a margin."""
    given = _given_options(options, "rasterize")
    ss = _structure_set(src)
    try:
        return _core_module._rasterize(ss._core, _roi_key(roi), float(voxel_mm), given)
    except ValueError as error:
        if isinstance(error, InputError):
            raise
        raise ValueError(_keywords_for_flags(str(error))) from None


def histogram(src, oar, target, *, volume_step_mm=0.5, surface_spacing_mm=0.5):
    """The overlap-volume histogram of ROI `oar` against ROI `target`, as
    ``dfrecon histogram``: returns a dict whose ``volume`` and ``surface``
    hold NumPy arrays ``distance_mm`` (signed distance of each cell of the
    OAR's volume or surface to the target's surface, < 0 inside it, sorted)
    and ``weight`` (each cell's mm³ or mm²) with their ``total``; the
    fraction of the OAR within d of the target is
    ``weight[distance_mm <= d].sum() / total``."""
    ss = _structure_set(src)
    return _core_module._histogram(ss._core, _roi_key(oar), _roi_key(target),
                                   float(volume_step_mm), float(surface_spacing_mm))


def _structure_set(src):
    if isinstance(src, StructureSet):
        return src
    if isinstance(src, (str, bytes, _os.PathLike)):
        return read_contours(src)
    raise TypeError("expected a StructureSet or a path, got %s" % type(src).__name__)


def _roi_key(roi):
    if roi is None or isinstance(roi, (str, int)) and not isinstance(roi, bool):
        return roi
    if isinstance(roi, Roi):
        return roi.name
    raise TypeError("roi: expected a name, a DICOM ROI number or a Roi, got %s"
                    % type(roi).__name__)


# ---- meshes ------------------------------------------------------------------


class Mesh:
    """A triangle surface: ``vertices`` (n, 3) float64 in patient mm and
    ``faces`` (m, 3) int32 indices, outward-oriented. Both are read-only views
    of the mesh's own arrays, not copies (``np.array(m.vertices)`` copies).

    ``Mesh(vertices, faces)`` makes one from arrays; :func:`reconstruct`,
    :func:`simplify` and :func:`read_mesh` return them. Reconstructed meshes
    carry ``name``, ``colour``, ``contour_volume_cc`` and ``report`` (the dict
    ``dfrecon reconstruct --json`` gives for the ROI). Hand the arrays to
    trimesh (``trimesh.Trimesh(m.vertices, m.faces)``) or pyvista
    (``pv.PolyData.from_regular_faces(m.vertices, m.faces)``)."""

    def __init__(self, vertices=None, faces=None, *, _core=None):
        if _core is None:
            if vertices is None or faces is None:
                raise TypeError("Mesh(vertices, faces): both arrays are needed")
            _core = _core_module._Mesh(vertices, faces)
        self._core = _core
        self._check = None

    @property
    def vertices(self):
        return self._core.vertices

    @property
    def faces(self):
        return self._core.faces

    @property
    def name(self):
        return self._core.name

    @property
    def colour(self):
        return self._core.colour

    @property
    def report(self):
        """The program's JSON report as a dict (reconstruct, simplify), or None."""
        return self._core.report

    @property
    def contour_volume_cc(self):
        """The planning system's volume of the contours it was made from, or None."""
        return self._core.contour_volume_cc

    def check(self):
        """As :func:`check`."""
        if self._check is None:
            self._check = self._core._check()
        return dict(self._check)

    @property
    def volume_cc(self):
        """The enclosed volume, cm³ (of a closed surface)."""
        return self.check()["volumeCc"]

    @property
    def area_mm2(self):
        return self.check()["areaMm2"]

    @property
    def valid_solid(self):
        """Closed, manifold, oriented, without self-intersection: a valid solid."""
        return self.check()["validSolid"]

    def write(self, path, binary=True):
        """Writes .ply, .stl, .obj, .off, .vtk or .vtp (by extension), atomically."""
        self._core._write(_os.fspath(path), bool(binary))

    def __repr__(self):
        return "Mesh(%s%d vertices, %d faces)" % (
            (repr(self.name) + ", ") if self.name else "", len(self.vertices), len(self.faces))


def read_mesh(path):
    """Reads a mesh file (.ply, .stl, .obj, .off)."""
    return Mesh(_core=_core_module._read_mesh(_os.fspath(path)))


def _mesh(m, what):
    if isinstance(m, Mesh):
        return m
    if isinstance(m, (str, bytes, _os.PathLike)):
        return read_mesh(m)
    raise TypeError("%s: expected a Mesh or a mesh file path, got %s" % (what, type(m).__name__))


# ---- reconstruct -------------------------------------------------------------

# Python names of the program's reconstruct options; the _mm forms name the unit.
_OPTION_ALIASES = {
    "pixel_mm": "pixel-mm",
    "contour_error": "contour-error",
    "contour_error_mm": "contour-error",
    "max_depth": "max-depth",
    "cap": "cap",
    "interpolation": "interpolation",
    "smooth_tolerance": "smooth-tolerance",
    "smooth_tolerance_mm": "smooth-tolerance",
    "cap_offset": "cap-offset",
    "cap_offset_mm": "cap-offset",
    "max_error": "max-error",
    "max_error_mm": "max-error",
}


def _option_text(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)
    return str(value)


def _given_options(options, function):
    """The reconstruction keywords as the program's option names and texts."""
    given = []
    for key, value in options.items():
        if key not in _OPTION_ALIASES:
            raise TypeError("%s() got an unexpected option %r (options: %s)"
                            % (function, key, ", ".join(sorted(_OPTION_ALIASES))))
        if value is not None:
            given.append((_OPTION_ALIASES[key], _option_text(value)))
    return given


def reconstruct(src, roi=None, *, jobs=0, neighbours="independent", **options):
    """Reconstructs ROI `roi` of `src` (a :class:`StructureSet` or a path to
    contours) into a closed :class:`Mesh`, as ``dfrecon reconstruct`` does:
    same surface, same triangles, same report.

    `roi` is a name, a DICOM ROI number, or a :class:`Roi`; None takes the only
    ROI, or, when the set holds several, reconstructs every ROI with contours
    and returns ``{name: Mesh}`` in file order. Options, as the program's
    (units mm): ``pixel_mm`` (0: automatic), ``contour_error_mm`` (0),
    ``max_depth`` (4), ``cap`` ('flat', 'dome', 'none'), ``cap_offset_mm``
    (automatic), ``interpolation`` ('smooth', 'linear'),
    ``smooth_tolerance_mm`` (0.05), ``max_error_mm`` (0: no simplification).
    Several ROIs are reconstructed ``jobs`` at a time (0: one per core), each
    worker with its own OpenCL queue, as ``reconstruct --all --jobs``; an ROI
    that cannot be reconstructed (its ``defect``) raises its error. With
    several ROIs, ``neighbours="apart"`` moves those whose contours overlap on
    no plane out of each other where their surfaces overlap between the
    planes, as ``reconstruct --all --neighbours apart`` (before any
    simplification; each mesh's report gives its volume after the move).
    """
    if neighbours not in ("independent", "apart"):
        raise ValueError("neighbours must be 'independent' or 'apart', not %r" % (neighbours,))
    given = _given_options(options, "reconstruct")
    ss = _structure_set(src)
    try:
        if roi is None and len(ss.rois) > 1:
            names = [r.name for r in ss.rois if len(r.contours) > 0 or r.defect]
            if len(set(names)) != len(names):
                raise ValueError("the structure set has ROIs of one name; reconstruct them by number")
            cores = _core_module._reconstruct_many(ss._core, names, given, int(jobs),
                                                   neighbours == "apart")
            return {name: Mesh(_core=core) for name, core in zip(names, cores)}
        return Mesh(_core=_core_module._reconstruct(ss._core, _roi_key(roi), given))
    except ValueError as error:
        if isinstance(error, InputError):
            raise
        raise ValueError(_keywords_for_flags(str(error))) from None


# The program's option names in messages, as this module's keywords: a
# Python user never typed "--pixel-mm".
_KEYWORD_OF_FLAG = {"--" + flag: keyword for keyword, flag in _OPTION_ALIASES.items()
                    if keyword.endswith("_mm") or keyword in ("max_depth", "cap", "interpolation")}


def _keywords_for_flags(message):
    for flag in sorted(_KEYWORD_OF_FLAG, key=len, reverse=True):
        message = message.replace(flag, _KEYWORD_OF_FLAG[flag])
    return message


# ---- fields ------------------------------------------------------------------


class Field:
    """Distances on a regular grid: ``values`` (float32, mm, negative inside),
    ``origin`` (the centre of the first sample, a point: x, y[, z]),
    ``spacing`` (mm per index step: for :func:`distance_field` in the array's
    axis order z, y, x, with ``directions`` likewise; slice fields have the
    same step along both in-plane axes), and for slice fields ``planes``
    (each plane's position)."""

    def __init__(self, d):
        self.__dict__.update(d)

    def __repr__(self):
        return "Field(shape=%s, origin=%s, spacing=%s)" % (
            self.values.shape, self.origin, self.spacing)


def slice_fields(src, roi=None, *, pixel_mm=0.0):
    """The exact signed 2D distance field of every plane of the ROI (reconstruction
    paper §2.1): ``values`` of shape (planes, height, width), pixel (i, j) of
    plane k centred at (origin[0] + i·spacing[0], origin[1] + j·spacing[1]) in
    the plane's coordinates at position ``planes[k]``."""
    ss = _structure_set(src)
    return Field(_core_module._slice_fields(ss._core, _roi_key(roi), float(pixel_mm)))


def distance_field(src, roi=None, *, pixel_mm=0.0, isotropic=False):
    """The ROI's 3D signed distance volume as ``dfrecon field`` computes it
    (in-plane Euclidean distance + |dz|: never below the Euclidean distance):
    ``values`` of shape (nz, ny, nx); ``spacing`` (mm per index step) and
    ``directions`` (each axis's unit vector, patient LPS) in the array's own
    axis order (z, y, x: the plane normal, then the planes' two axes; for an
    axial stack (0, 0, 1), (0, 1, 0), (1, 0, 0)); ``origin`` the LPS point
    (x, y, z) of voxel [0, 0, 0]'s centre, so voxel [k, j, i] is at origin +
    k·spacing[0]·directions[0] + j·spacing[1]·directions[1] +
    i·spacing[2]·directions[2]. In the planes the step is ``pixel_mm``; along
    the normal it is half the smallest gap between planes, whatever
    ``pixel_mm`` (so that every plane and both cap planes lie on a layer of
    voxels: 0.667 mm where two planes are 1.33 mm apart), or ``pixel_mm``
    itself with ``isotropic=True``."""
    ss = _structure_set(src)
    return Field(_core_module._distance_field(ss._core, _roi_key(roi), float(pixel_mm),
                                              bool(isotropic)))


# ---- meshes: simplify, maps, compare, check ---------------------------------------


def simplify(mesh, max_error_mm):
    """The mesh simplified by edge collapses within `max_error_mm` of it in both
    directions (reconstruction paper §6.2), verified independently; the
    result's ``report`` is ``dfrecon simplify --json``'s simplification."""
    m = _mesh(mesh, "simplify")
    return Mesh(_core=_core_module._simplify(m._core, float(max_error_mm)))


def surface_distance_maps(meshes, *, names=None, max_distance_mm=None, texels=512,
                          sampling_mm=0.0, pairs=False):
    """Per mesh, at every vertex, the signed distance to the nearest other mesh
    (negative inside it), which mesh that is and its closest point (surface
    distance maps paper; what ``dfrecon sdm`` writes).

    Returns one dict per mesh, in order: ``name``, ``distance_mm`` (n,)
    float64 (inf beyond ``max_distance_mm``), ``nearest`` (n,) int32 (the
    index of the nearest mesh, -1 beyond the band), ``closest_point`` (n, 3)
    and ``sampling_bound_mm``. With ``pairs=True``, returns ``(maps, pairs)``,
    ``pairs`` a dict per pair of meshes: separation (sampled, with its bound),
    whether their surfaces intersect or one is inside the other, penetration.
    ``sampling_mm`` > 0 sizes the atlas for that sampling bound instead of
    ``texels`` a side."""
    ms = [_mesh(m, "surface_distance_maps") for m in meshes]
    if len(ms) < 2:
        raise ValueError("surface_distance_maps needs at least two meshes")
    if names is None:
        names = [m.name or ("mesh%d" % i) for i, m in enumerate(ms)]
    maps, pair_list = _core_module._surface_distance_maps(
        [m._core for m in ms], list(names), float(max_distance_mm or 0), int(texels),
        float(sampling_mm), bool(pairs))
    return (maps, pair_list) if pairs else maps


def compare(a, b, *, roi_a=None, roi_b=None, spacing_mm=0.2, tolerance_mm=1.0):
    """How two structures agree, with ``dfrecon compare --json``'s keys: volumes,
    Dice, Jaccard (on the surfaces, within intersectionBoundMm3), Hausdorff,
    HD95, mean surface distance, surface Dice (each within spacing_mm),
    centroid distance, and for two contour inputs
    ``onPlanes``, the planning system's per-plane overlap and added path
    length. `a` and `b` are Meshes or mesh files, or StructureSets / contour
    files with ``roi_a``, ``roi_b`` (reconstructed as the program does)."""
    def contours(x):
        return isinstance(x, StructureSet) or (
            isinstance(x, (str, _os.PathLike)) and not _core_module._is_mesh_path(_os.fspath(x)))
    if contours(a) and contours(b):
        return _core_module._compare_contours(
            _structure_set(a)._core, _roi_key(roi_a), _structure_set(b)._core, _roi_key(roi_b),
            float(spacing_mm), float(tolerance_mm))
    def solid(x, roi, what):
        if contours(x):
            return reconstruct(x, roi if roi is not None else None)
        return _mesh(x, what)
    ma, mb = solid(a, roi_a, "compare a"), solid(b, roi_b, "compare b")
    return _core_module._compare(ma._core, mb._core, float(spacing_mm), float(tolerance_mm))


def compare_sets(a, b, *, match=None, spacing_mm=0.2, tolerance_mm=1.0):
    """Two structure sets (or contour files) compared ROI by ROI, as ``dfrecon
    compare A B`` does with several ROIs: ROIs paired by ``match`` (a dict
    ``{name_in_a: name_in_b}``), then by equal names, then by names equal
    with case, spaces and punctuation ignored. Returns a dict: ``pairs``, a
    list of dicts with ``roiA``, ``roiB``, ``matchedBy`` and every key of
    :func:`compare` (or ``error`` and ``exitCode`` where that pair failed),
    and the ROIs in no pair: ``unmatchedA``/``B``, ``duplicateA``/``B``
    (a name used twice in a set), ``emptyA``/``B`` (no contours)."""
    sa, sb = _structure_set(a), _structure_set(b)
    entries = ["%s=%s" % (k, v) for k, v in (match or {}).items()]
    return _core_module._compare_sets(sa._core, sb._core, entries, float(spacing_mm),
                                      float(tolerance_mm))


def segment(mesh, regions=10, *, speed="attractive", disks=True):
    """Geodesic centroidal segmentation of a surface into about `regions`
    patches, as ``dfrecon segment -k REGIONS`` (farthest-point seeds, geodesic
    Voronoi regions, geodesic Lloyd, each region a topological disk unless
    ``disks=False``). `speed` as ``--speed``: 'attractive' (borders settle on
    creases, the default), 'repulsive' or 'uniform'. Returns a dict:
    ``vertex_region`` and ``face_region`` (int32 arrays, -1 for none),
    ``seeds``, ``regions`` (each with ``areaMm2``, ``perimeterMm``,
    ``compactness``, ``faces``, ``disk``), ``iterations``, ``converged``."""
    m = _mesh(mesh, "segment")
    return _core_module._segment(m._core, int(regions), str(speed), bool(disks))


def geodesic(mesh, sources, *, speed="uniform", curvature_weight_mm=0.0):
    """Geodesic distances over the surface from the vertices `sources` (an
    int or a list), as ``dfrecon geodesic --from ... --solver fm``: a dict
    with ``distance_mm`` (float64 per vertex, inf where unreached; weighted
    time for a speed other than 'uniform') and ``nearest_source`` (the
    index into `sources` of each vertex's nearest, -1 where unreached)."""
    m = _mesh(mesh, "geodesic")
    vertices = [int(sources)] if isinstance(sources, int) else [int(v) for v in sources]
    return _core_module._geodesic(m._core, vertices, str(speed), float(curvature_weight_mm))


def check(mesh):
    """Whether the mesh is a valid closed solid, with ``dfrecon check --json``'s
    keys: validSolid, watertight, volumeMm3, volumeCc, areaMm2, genus, the
    defects' counts and where they are."""
    return _mesh(mesh, "check").check()
