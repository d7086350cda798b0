#pragma once
// What a mesh carries besides its geometry: named arrays with one value per
// vertex or per face (distances, nearest-object ids, directions, region
// ids), colours, and the structure it is the surface of. The writers of
// io/mesh/AttributedMesh (PLY) and io/mesh/VtkPolyData (VTK, VTP) take it.
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/Vec3.hpp"
#include "io/images/Colours.hpp"
#include "io/mesh/StructureTag.hpp"

namespace dfrecon {

/// A named array with one value per vertex or per face.
template <class T>
struct NamedArray {
    std::string name;
    std::vector<T> values;
};

/// Every array is in the mesh's vertex or face order, and an empty colour
/// array means no colours.
struct MeshAttributes {
    std::vector<NamedArray<float>> vertexScalars;
    std::vector<NamedArray<std::int32_t>> vertexLabels;
    std::vector<NamedArray<Vec3>> vertexVectors;  // VTK only
    std::vector<Rgb> vertexColours;
    std::vector<NamedArray<std::int32_t>> faceLabels;
    std::vector<Rgb> faceColours;
    StructureTag structure;

    bool hasFaceData() const { return !faceLabels.empty() || !faceColours.empty(); }
};

/// Throws std::invalid_argument naming the array when one has not
/// `vertices` or `faces` values. O(number of arrays).
void checkAttributeSizes(const MeshAttributes& attributes, std::size_t vertices, std::size_t faces);

}  // namespace dfrecon
