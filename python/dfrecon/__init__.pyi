# Type stubs of the dfrecon Python module (docs/python.md).
from os import PathLike
from typing import Any, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str

_Path = Union[str, PathLike]
_Colour = Tuple[int, int, int]
_RoiKey = Union[str, int, "Roi", None]

class InputError(ValueError):
    file: str
    line: int
class InvalidResultError(RuntimeError): ...
class DeviceError(RuntimeError): ...

def set_device(spec: str) -> None: ...
def device_name() -> str: ...

class Roi:
    name: str
    number: Optional[int]
    colour: Optional[_Colour]
    interpreted_type: Optional[str]
    planes: npt.NDArray[np.float64]
    contours: List[npt.NDArray[np.float64]]
    orientation: str
    contour_volume_cc: float
    defect: Optional[str]
    contour_reading: Dict[str, Any]
    warnings: List[str]

class StructureSet:
    rois: List[Roi]
    @classmethod
    def from_contours(
        cls,
        rois: Mapping[str, Sequence[npt.ArrayLike]],
        colours: Optional[Mapping[str, _Colour]] = ...,
    ) -> "StructureSet": ...
    @property
    def format(self) -> str: ...
    @property
    def source(self) -> str: ...
    @property
    def warnings(self) -> List[str]: ...
    @property
    def names(self) -> List[str]: ...
    def __len__(self) -> int: ...
    def __iter__(self) -> Iterator[Roi]: ...
    def __getitem__(self, key: Union[str, int]) -> Roi: ...
    def __contains__(self, key: Union[str, int]) -> bool: ...
    def write_slices(self, path: _Path) -> None: ...
    def write(self, path: _Path, *, like: Optional[_Path] = ...) -> None: ...

def read_contours(
    path: _Path,
    *,
    label_table: Optional[_Path] = ...,
    accept_intensity: bool = ...,
) -> StructureSet: ...

class Mesh:
    def __init__(self, vertices: npt.ArrayLike, faces: npt.ArrayLike) -> None: ...
    @property
    def vertices(self) -> npt.NDArray[np.float64]: ...
    @property
    def faces(self) -> npt.NDArray[np.int32]: ...
    @property
    def name(self) -> str: ...
    @property
    def colour(self) -> Optional[_Colour]: ...
    @property
    def report(self) -> Optional[Dict[str, Any]]: ...
    @property
    def contour_volume_cc(self) -> Optional[float]: ...
    @property
    def volume_cc(self) -> float: ...
    @property
    def area_mm2(self) -> float: ...
    @property
    def valid_solid(self) -> bool: ...
    def check(self) -> Dict[str, Any]: ...
    def write(self, path: _Path, binary: bool = ...) -> None: ...

def read_mesh(path: _Path) -> Mesh: ...
@overload
def reconstruct(
    src: Union[StructureSet, _Path], roi: Union[str, int, Roi], *, jobs: int = ..., neighbours: str = ..., **options: Any
) -> Mesh: ...
@overload
def reconstruct(
    src: Union[StructureSet, _Path], roi: None = ..., *, jobs: int = ..., neighbours: str = ..., **options: Any
) -> Union[Mesh, Dict[str, Mesh]]: ...

def margin(
    src: Union[StructureSet, _Path],
    roi: Union[str, int, Roi],
    mm: Union[float, Sequence[float]],
    *,
    name: Optional[str] = ...,
    step_mm: float = ...,
    min_area_mm2: float = ...,
    colour: Optional[Tuple[int, int, int]] = ...,
    roi_type: Optional[str] = ...,
) -> Tuple[StructureSet, Dict[str, Any]]: ...
def combine(
    src: Union[StructureSet, _Path],
    definition: str,
    *,
    step_mm: float = ...,
    min_area_mm2: float = ...,
    colour: Optional[Tuple[int, int, int]] = ...,
    roi_type: Optional[str] = ...,
) -> Tuple[StructureSet, Dict[str, Any]]: ...
def rasterize(
    src: Union[StructureSet, _Path], roi: _RoiKey = ..., *, voxel_mm: float = ..., **options: Any
) -> Dict[str, Any]: ...
def histogram(
    src: Union[StructureSet, _Path],
    oar: Union[str, int, Roi],
    target: Union[str, int, Roi],
    *,
    volume_step_mm: float = ...,
    surface_spacing_mm: float = ...,
) -> Dict[str, Any]: ...

class Field:
    values: npt.NDArray[np.float32]
    origin: Tuple[float, ...]
    spacing: Tuple[float, ...]
    planes: npt.NDArray[np.float64]  # slice_fields only
    directions: Tuple[Tuple[float, float, float], ...]  # distance_field only, array order (z, y, x)
    orientation: str  # slice_fields only

def slice_fields(src: Union[StructureSet, _Path], roi: _RoiKey = ..., *, pixel_mm: float = ...) -> Field: ...
def distance_field(
    src: Union[StructureSet, _Path], roi: _RoiKey = ..., *, pixel_mm: float = ..., isotropic: bool = ...
) -> Field: ...
def simplify(mesh: Union[Mesh, _Path], max_error_mm: float) -> Mesh: ...
def surface_distance_maps(
    meshes: Sequence[Union[Mesh, _Path]],
    *,
    names: Optional[Sequence[str]] = ...,
    max_distance_mm: Optional[float] = ...,
    texels: int = ...,
    sampling_mm: float = ...,
    pairs: bool = ...,
) -> Union[List[Dict[str, Any]], Tuple[List[Dict[str, Any]], List[Dict[str, Any]]]]: ...
def segment(
    mesh: Union[Mesh, _Path], regions: int = ..., *, speed: str = ..., disks: bool = ...
) -> Dict[str, Any]: ...
def geodesic(
    mesh: Union[Mesh, _Path],
    sources: Union[int, Sequence[int]],
    *,
    speed: str = ...,
    curvature_weight_mm: float = ...,
) -> Dict[str, Any]: ...
def compare_sets(
    a: Union[StructureSet, _Path],
    b: Union[StructureSet, _Path],
    *,
    match: Optional[Dict[str, str]] = ...,
    spacing_mm: float = ...,
    tolerance_mm: float = ...,
) -> Dict[str, Any]: ...
def compare(
    a: Union[Mesh, StructureSet, _Path],
    b: Union[Mesh, StructureSet, _Path],
    *,
    roi_a: _RoiKey = ...,
    roi_b: _RoiKey = ...,
    spacing_mm: float = ...,
    tolerance_mm: float = ...,
) -> Dict[str, Any]: ...
def check(mesh: Union[Mesh, _Path]) -> Dict[str, Any]: ...
