#pragma once
// What `dfrecon segment` and `dfrecon geodesic` share: reading the mesh
// into the solvers' graph, and writing PLY files that carry results as
// properties (per-face region ids, per-vertex distances) next to colours a
// viewer shows.
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

/// Throws std::invalid_argument (exit 1) unless `path` ends in .ply: only
/// PLY carries the per-face and per-vertex properties.
void requirePlyOutput(const std::string& path);

/// Writes `mesh` with an int face property "region" (-1: unreached) and
/// face colours, one colour per region.
void writeRegionsPly(TriMesh mesh, const std::vector<int>& faceRegion, const std::string& path,
                     bool binary);

/// Writes `mesh` with float vertex properties "distance" (mm, or the
/// weighted distance for a non-uniform speed; -1 where unreached) and int
/// "source" (the index of the nearest source), and vertex colours from
/// blue (0) to red (the largest distance).
void writeDistancePly(TriMesh mesh, const std::vector<double>& distance,
                      const std::vector<int>& source, const std::string& path, bool binary);

}  // namespace dfrecon::app
