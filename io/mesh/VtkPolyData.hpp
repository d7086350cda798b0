#pragma once
// Triangle meshes with their per-vertex and per-face arrays in VTK's two
// polydata formats, the ones ParaView and 3D Slicer open:
//   legacy VTK (.vtk)  "# vtk DataFile Version 3.0", BINARY (big-endian):
//                      points as double (exact), POLYGONS, POINT_DATA and
//                      CELL_DATA; what every VTK-based tool reads. Not
//                      ASCII: VTK's ASCII reader (9.1) refuses the "nan"
//                      and "inf" its own writer writes
//   VTK XML (.vtp)     PolyData version 1.0, every array binary (base64,
//                      UInt64 byte counts): points Float64 (exact), polys
//                      as Int64 connectivity and offsets, PointData and
//                      CellData; a third of the size and faster to load
// Both carry the same arrays under the same names: scalars as float,
// labels as 32-bit int, vectors as 3 components, colours as unsigned char
// RGB named "colour"; the structure (io/mesh/StructureTag) is field data, the
// string array "roi_name" and the unsigned char array "roi_colour".
// VTK itself is not a dependency; tests read both files with VTK's own
// readers (tests/io/vtk_read_check.py).
#include <iosfwd>

#include "geometry/TriangleSoup.hpp"
#include "io/mesh/MeshAttributes.hpp"

namespace dfrecon {

/// Writes `soup` with `attributes` as binary legacy VTK polydata to `out`.
/// Throws std::invalid_argument (before writing anything) when an array's
/// size is not the vertex or face count. O(vertices + faces).
void writeVtkLegacy(std::ostream& out, const TriangleSoup& soup, const MeshAttributes& attributes);

/// The same as VTK XML PolyData (.vtp). O(vertices + faces).
void writeVtkXml(std::ostream& out, const TriangleSoup& soup, const MeshAttributes& attributes);

}  // namespace dfrecon
