#pragma once
// Helpers the segment tests share: meshes with their reference distances.
#include <cmath>
#include <cstdint>
#include <vector>

#include "segment/MeshGraph.hpp"
#include "shapes/MeshShapes.hpp"

namespace dfrecon::testing {

/// Great-circle distance on the sphere of radius r centred at the origin.
inline double greatCircle(Vec3 a, Vec3 b, double r) {
    const double c = dot(a, b) / (r * r);
    return r * std::acos(std::max(-1.0, std::min(1.0, c)));
}

/// The vertex nearest to p.
inline int nearestVertex(const MeshGraph& graph, Vec3 p) {
    int best = 0;
    for (int v = 1; v < graph.vertexCount(); ++v)
        if (length(graph.point(v) - p) < length(graph.point(best) - p)) best = v;
    return best;
}

/// A 3×3 grid of unit squares and, 10 mm away, a separate 2×2 one (its
/// vertices from index 16 on): a front from the first never reaches it.
inline TriangleSoup twoComponents() {
    TriangleSoup two = squareGrid(3, 3, 1.0);
    const TriangleSoup other = squareGrid(2, 2, 1.0);
    const std::uint32_t offset = std::uint32_t(two.points.size());
    for (Vec3 p : other.points) two.points.push_back(p + Vec3{10, 0, 0});
    for (auto t : other.triangles)
        two.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    return two;
}

struct ErrorStats {
    double mean = 0, max = 0;
};

/// |time − reference| over the vertices, mean and max.
template <class Reference>
ErrorStats errorAgainst(const MeshGraph& graph, const std::vector<double>& time,
                        Reference&& reference) {
    ErrorStats e;
    for (int v = 0; v < graph.vertexCount(); ++v) {
        const double d = std::abs(time[std::size_t(v)] - reference(graph.point(v)));
        e.mean += d;
        e.max = std::max(e.max, d);
    }
    e.mean /= graph.vertexCount();
    return e;
}

}  // namespace dfrecon::testing
