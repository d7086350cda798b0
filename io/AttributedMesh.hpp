#pragma once
// Meshes carrying results per vertex (distances, nearest-object ids,
// directions) and per face (region ids), with colours, in the files that
// viewers read them from:
//   PLY   MeshLab, Blender, CloudCompare: colours, and each scalar or label
//         as a vertex or face property (OpenMesh's writer, custom
//         properties); a vertex scalar named "quality" is what MeshLab
//         colours and filters by
//   VTK   ParaView and 3D Slicer: legacy polydata, vertex arrays as
//         POINT_DATA and face arrays as CELL_DATA (written here: ParaView's
//         PLY reader ignores custom properties, and VTK itself is not a
//         dependency)
// Every writer is O(vertices + faces) and writes atomically (io/AtomicWrite).
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/TriMesh.hpp"
#include "geometry/TriangleSoup.hpp"
#include "io/Colours.hpp"

namespace dfrecon {

/// A named array with one value per vertex or per face.
template <class T>
struct NamedArray {
    std::string name;
    std::vector<T> values;
};

/// What a mesh carries besides its geometry; every array is in the mesh's
/// vertex or face order, and an empty colour array means no colours.
struct MeshAttributes {
    std::vector<NamedArray<float>> vertexScalars;
    std::vector<NamedArray<std::int32_t>> vertexLabels;
    std::vector<NamedArray<Vec3>> vertexVectors;  // VTK only
    std::vector<Rgb> vertexColours;
    std::vector<NamedArray<std::int32_t>> faceLabels;
    std::vector<Rgb> faceColours;
};

/// PLY (binary unless `binary` is false) of `mesh`'s vertices and faces in
/// their order, with the colours and every scalar and label as a property
/// under its name (vectors are left out). Throws std::invalid_argument when
/// an array's size is not the vertex or face count, std::runtime_error on a
/// failed write.
void writeAttributedPly(TriMesh mesh, const MeshAttributes& attributes, const std::string& path,
                        bool binary = true);

/// The same for a soup, through toTriMesh: faces OpenMesh refuses
/// (non-manifold) are left out of the PLY, and then face arrays, which
/// would no longer line up, are refused (std::invalid_argument).
void writeAttributedPly(const TriangleSoup& soup, const MeshAttributes& attributes,
                        const std::string& path, bool binary = true);

/// ASCII legacy VTK polydata (.vtk) with every vertex array as POINT_DATA
/// and every face array as CELL_DATA (colours as unsigned-char
/// COLOR_SCALARS named "colour"). Throws as writeAttributedPly does.
void writeAttributedVtk(const TriangleSoup& soup, const MeshAttributes& attributes,
                        const std::string& path);
void writeAttributedVtk(const TriMesh& mesh, const MeshAttributes& attributes,
                        const std::string& path);

/// Whether `path` names a format these writers know: .ply or .vtk, any case.
bool isAttributedMeshPath(const std::string& path);

/// writeAttributedPly or writeAttributedVtk by the extension of `path`
/// (`binary` applies to PLY); std::invalid_argument for another extension.
void writeAttributedMesh(TriMesh mesh, const MeshAttributes& attributes, const std::string& path,
                         bool binary = true);

}  // namespace dfrecon
