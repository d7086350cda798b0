#pragma once
// The connectivity and geometry every geodesic stage reads, in flat arrays
// built once from a mesh: vertex positions, triangles, the triangles around
// each vertex (compressed rows) and each triangle's neighbour across each of
// its edges. Flat arrays rather than OpenMesh's half-edges because the
// solvers touch them millions of times and because the OpenCL solver needs
// them as plain buffers anyway.
#include <array>
#include <vector>

#include "geometry/TriMesh.hpp"
#include "geometry/TriangleSoup.hpp"
#include "geometry/Vec3.hpp"

namespace dfrecon {

/// A read-only view of consecutive ints, for range-for over adjacency rows.
struct IndexRange {
    const int* first = nullptr;
    const int* last = nullptr;
    const int* begin() const { return first; }
    const int* end() const { return last; }
    std::size_t size() const { return std::size_t(last - first); }
};

class MeshGraph {
  public:
    MeshGraph() = default;

    /// Builds the adjacency of `triangles` over `points` (coordinates in mm).
    /// Orientation need not be consistent. Throws std::invalid_argument when
    /// an index is out of range, a triangle repeats a vertex, or an edge has
    /// more than two triangles (not a 2-manifold). O(T · d) for T triangles
    /// and largest vertex degree d.
    MeshGraph(std::vector<Vec3> points, std::vector<std::array<int, 3>> triangles);

    static MeshGraph fromSoup(const TriangleSoup& soup);
    /// The mesh's vertex and face numbering is kept.
    static MeshGraph fromMesh(const TriMesh& mesh);

    int vertexCount() const { return int(points_.size()); }
    int triangleCount() const { return int(triangles_.size()); }
    const std::vector<Vec3>& points() const { return points_; }
    const std::vector<std::array<int, 3>>& triangles() const { return triangles_; }
    Vec3 point(int v) const { return points_[std::size_t(v)]; }
    const std::array<int, 3>& triangle(int t) const { return triangles_[std::size_t(t)]; }

    /// The triangles that have `v` as a corner, in no particular order.
    IndexRange trianglesAround(int v) const {
        const int* base = vertexTriangles_.data();
        return {base + vertexTriangleFirst_[std::size_t(v)],
                base + vertexTriangleFirst_[std::size_t(v) + 1]};
    }
    /// The triangle across the edge opposite corner `corner` (0..2) of `t`,
    /// i.e. across edge (corner+1, corner+2); -1 on a mesh boundary.
    int neighbour(int t, int corner) const { return neighbours_[std::size_t(t)][corner]; }
    /// The corner (0..2) of `t` that is vertex `v`, or -1.
    int cornerOf(int t, int v) const;

    double triangleArea(int t) const;
    double totalArea() const;
    /// One third of the area of the triangles around each vertex (the
    /// lumped mass used for first-order integration over the surface).
    std::vector<double> vertexAreas() const;
    /// Mean length of the edges (each counted once). O(T).
    double meanEdgeLength() const;
    /// Number of edges with a single triangle.
    int boundaryEdgeCount() const;

  private:
    std::vector<Vec3> points_;
    std::vector<std::array<int, 3>> triangles_;
    std::vector<int> vertexTriangleFirst_;  // vertexCount() + 1 offsets
    std::vector<int> vertexTriangles_;
    std::vector<std::array<int, 3>> neighbours_;
};

}  // namespace dfrecon
