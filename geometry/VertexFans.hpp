#pragma once
// The fan of triangles around each vertex of a closed surface, in order,
// with the planes that cut space into one sector per triangle of the fan:
// what deviationBound's fan rule (kernels/fan_bound.cl) needs, built once
// per surface.
#include <cstdint>
#include <vector>

#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

class VertexFans {
  public:
    /// The most neighbours a fan may have (FAN_MAX in kernels/fan_bound.cl).
    static constexpr std::size_t kMaxNeighbours = 16;

    /// The fans of every vertex of `soup`. A vertex gets an empty fan when
    /// its triangles do not close into one cycle (a boundary or
    /// non-manifold vertex), when it has more than kMaxNeighbours
    /// neighbours, or when its neighbours do not turn exactly once about
    /// the fan's axis (the sum of its triangles' normals) in steps under
    /// 180°: only then do the sectors tile space, each convex. O(T).
    explicit VertexFans(const TriangleSoup& soup);

    /// Vertex v's neighbours are ring()[first()[v] .. first()[v + 1]),
    /// counter-clockwise about the axis; triangle i of its fan is
    /// (v, ring[i], ring[i + 1 mod m]), one of the soup's triangles.
    const std::vector<std::uint32_t>& first() const { return first_; }
    const std::vector<std::uint32_t>& ring() const { return ring_; }
    /// For each ring entry (the same index): the normal of the plane
    /// through v, the axis and that neighbour, positive on its
    /// counter-clockwise side. Sector i is where (x − v)·normal[i] ≥ 0 and
    /// (x − v)·normal[i + 1 mod m] ≤ 0.
    const std::vector<Vec3>& sectorNormals() const { return sectorNormals_; }

    std::size_t neighbours(std::uint32_t v) const { return first_[v + 1] - first_[v]; }

  private:
    std::vector<std::uint32_t> first_, ring_;
    std::vector<Vec3> sectorNormals_;
};

}  // namespace dfrecon
