#pragma once
// Meshes carrying results per vertex (distances, nearest-object ids,
// directions) and per face (region ids), with colours and the structure
// they are the surface of (io/mesh/MeshAttributes), in the files that viewers
// read them from:
//   PLY   MeshLab, Blender, CloudCompare: colours, and each scalar or label
//         as a vertex or face property (OpenMesh's writer, custom
//         properties); a vertex scalar named "quality" is what MeshLab
//         colours and filters by; the structure as header comments
//         "comment roi_name NAME" and "comment roi_colour R G B"
//   VTK   ParaView and 3D Slicer: legacy polydata (.vtk) or VTK XML
//         PolyData (.vtp), vertex arrays as point data and face arrays as
//         cell data (io/mesh/VtkPolyData: ParaView's PLY reader ignores custom
//         properties)
// Every writer is O(vertices + faces) and writes atomically (io/files/AtomicWrite).
#include <iosfwd>
#include <string>

#include "geometry/TriMesh.hpp"
#include "geometry/TriangleSoup.hpp"
#include "io/mesh/MeshAttributes.hpp"

namespace dfrecon {

/// PLY (binary unless `binary` is false) of `mesh`'s vertices and faces in
/// their order to `out`, with the colours and every scalar and label as a
/// property under its name (vectors are left out), per-vertex normals if
/// `vertexNormals`, and the structure's name and colour as header comments
/// after the format line. Coordinates are floats (OpenMesh's writer; ASCII
/// with kAsciiMeshDigits digits, each float exactly). Throws std::invalid_argument when an array's
/// size is not the vertex or face count (before writing anything),
/// std::runtime_error when OpenMesh fails.
/// The properties are added to the mesh: a const mesh is copied first, an
/// rvalue (std::move) gains them in place (io/mesh/MeshIO's writeMesh says why).
void writeAttributedPly(std::ostream& out, const TriMesh& mesh, const MeshAttributes& attributes,
                        bool binary, bool vertexNormals = false);
void writeAttributedPly(std::ostream& out, TriMesh&& mesh, const MeshAttributes& attributes,
                        bool binary, bool vertexNormals = false);

/// The same into the file `path`, atomically.
void writeAttributedPly(const TriMesh& mesh, const MeshAttributes& attributes,
                        const std::string& path, bool binary = true);
void writeAttributedPly(TriMesh&& mesh, const MeshAttributes& attributes, const std::string& path,
                        bool binary = true);

/// The same for a soup, through toTriMesh: faces OpenMesh refuses
/// (non-manifold) are left out of the PLY, and then face arrays, which
/// would no longer line up, are refused (std::invalid_argument).
void writeAttributedPly(const TriangleSoup& soup, const MeshAttributes& attributes,
                        const std::string& path, bool binary = true);

/// Whether `path` names a format these writers know: .ply, .vtk or .vtp,
/// any case.
bool isAttributedMeshPath(const std::string& path);

/// writeAttributedPly, or io/mesh/VtkPolyData's legacy (.vtk) or XML (.vtp)
/// writer, by the extension of `path` (`binary` applies to PLY), into the
/// file atomically; std::invalid_argument for another extension or a
/// wrong array size (nothing written).
void writeAttributedMesh(const TriMesh& mesh, const MeshAttributes& attributes,
                         const std::string& path, bool binary = true);
void writeAttributedMesh(const TriangleSoup& soup, const MeshAttributes& attributes,
                         const std::string& path, bool binary = true);

}  // namespace dfrecon
