#pragma once
// What `dfrecon segment` and `dfrecon geodesic` share: reading the mesh
// into the solvers' graph, and writing the results as mesh attributes
// (io/mesh/AttributedMesh: per-face region ids, per-vertex distances) next to
// the colours a viewer shows (io/images/Colours).
#include <string>
#include <vector>

#include "geometry/TriMesh.hpp"
#include "segment/MeshGraph.hpp"

namespace dfrecon::app {

/// The mesh at `path` and its graph (same vertex and face numbering).
/// Throws InputError naming the file when it cannot be read or is not a
/// 2-manifold.
struct GeodesicInput {
    TriMesh mesh;
    MeshGraph graph;
};
GeodesicInput readGeodesicInput(const std::string& path);

/// Throws std::invalid_argument (exit 1) unless `path` ends in .ply, .vtk
/// or .vtp: the mesh formats that carry per-face and per-vertex values.
void requireAttributedMeshOutput(const std::string& path);

/// Writes `mesh` (PLY, VTK or VTP by the extension; `binary` for PLY) with an
/// int face property "region" (-1: unreached) and face colours, one
/// categorical colour per region. O(V + F).
void writeRegions(TriMesh mesh, const std::vector<int>& faceRegion, const std::string& path,
                  bool binary);

/// Writes `mesh` (PLY, VTK or VTP by the extension; `binary` for PLY) with float
/// vertex property "distance" (mm, or the weighted distance for a
/// non-uniform speed; -1 where unreached), int "source" (the index of the
/// nearest source), and vertex colours on the sequential ramp from 0 to the
/// largest distance (grey where unreached). O(V + F).
void writeDistances(TriMesh mesh, const std::vector<double>& distance,
                    const std::vector<int>& source, const std::string& path, bool binary);

}  // namespace dfrecon::app
