#pragma once
// Meshes carrying per-vertex data (distances, nearest-object ids, colours,
// directions) in the files that viewers read it from:
//   PLY   MeshLab, Blender, CloudCompare: colours, and each scalar or label
//         as a vertex property (OpenMesh's writer, custom properties); a
//         scalar named "quality" is what MeshLab colours and filters by
//   VTK   ParaView and 3D Slicer: legacy polydata with POINT_DATA arrays
//         (written here: ParaView's PLY reader ignores custom properties,
//         and VTK itself is not a dependency)
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

struct VertexData {
    std::vector<std::pair<std::string, std::vector<float>>> scalars;
    std::vector<std::pair<std::string, std::vector<std::int32_t>>> labels;
    std::vector<std::pair<std::string, std::vector<Vec3>>> vectors;  // VTK only
    std::vector<std::array<std::uint8_t, 3>> colours;                // RGB; empty for none
};

/// Binary PLY with vertex colours and every scalar and label as a vertex
/// property; each array must have one value per point. Written atomically.
/// Throws std::invalid_argument on mismatched sizes, std::runtime_error on
/// a failed write.
void writePlyWithVertexData(const TriangleSoup& soup, const VertexData& data,
                            const std::string& path);

/// ASCII legacy VTK polydata (.vtk) with every array as POINT_DATA (colours
/// as unsigned-char COLOR_SCALARS). Written atomically. O(points + triangles).
void writeVtkWithVertexData(const TriangleSoup& soup, const VertexData& data,
                            const std::string& path);

}  // namespace dfrecon
