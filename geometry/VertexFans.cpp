#include "geometry/VertexFans.hpp"

#include <utility>

namespace dfrecon {

namespace {

// det(n, a, b): > 0 when b is less than 180° counter-clockwise of a about n.
double turn(Vec3 n, Vec3 a, Vec3 b) {
    return dot(n, cross(a, b));
}

// Vertex v's neighbours in order, or none when its triangles (given as the
// pairs (b, c) of each triangle (v, b, c)) do not close into one cycle.
std::vector<std::uint32_t> cycleOf(
    const std::vector<std::pair<std::uint32_t, std::uint32_t>>& links) {
    std::vector<std::uint32_t> cycle;
    if (links.empty()) return cycle;
    std::uint32_t at = links[0].first;
    for (std::size_t step = 0; step < links.size(); ++step) {
        cycle.push_back(at);
        const std::uint32_t from = at;
        for (const auto& [b, c] : links)
            if (b == from) {
                at = c;
                break;
            }
        if (at == from) return {};  // no triangle leaves this neighbour
        // Back at the start before every triangle is used: more than one
        // cycle (a vertex where two fans touch).
        if (at == links[0].first && step + 1 < links.size()) return {};
    }
    if (at != links[0].first) return {};
    return cycle;
}

// The sector normals of v's fan, or none when its neighbours do not turn
// exactly once about the axis in steps under 180°.
std::vector<Vec3> sectorNormalsOf(Vec3 v, const std::vector<Vec3>& ring) {
    const std::size_t m = ring.size();
    Vec3 axis{0, 0, 0};
    for (std::size_t i = 0; i < m; ++i) axis = axis + cross(ring[i] - v, ring[(i + 1) % m] - v);
    // Measured from ring[0], each step turns by under 180° and the angles
    // only grow: they pass from the upper half (0°, 180°) through 180° to
    // the lower half (180°, 360°) and never come back.
    const Vec3 u0 = ring[0] - v;
    const double axis2 = dot(axis, axis);
    int half = 0;  // 0 upper, 1 exactly 180°, 2 lower
    std::vector<Vec3> normals;
    for (std::size_t i = 0; i < m; ++i) {
        const Vec3 u = ring[i] - v;
        if (!(turn(axis, u, ring[(i + 1) % m] - v) > 0)) return {};
        if (i > 0) {
            const double side = turn(axis, u0, u);
            int now = side > 0 ? 0 : 2;
            if (!(side != 0)) {
                // On u0's line: opposite it (180°) is fine, along it is a
                // second turn. Compared as projections across the axis.
                if (!(dot(u0, u) * axis2 - dot(u0, axis) * dot(u, axis) < 0)) return {};
                now = 1;
            }
            if (now < half) return {};
            half = now;
        }
        normals.push_back(cross(axis, u));
    }
    return normals;
}

}  // namespace

VertexFans::VertexFans(const TriangleSoup& soup) {
    const std::size_t n = soup.points.size();
    std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> links(n);
    for (const auto& t : soup.triangles)
        for (std::size_t k = 0; k < 3; ++k) links[t[k]].push_back({t[(k + 1) % 3], t[(k + 2) % 3]});
    first_.reserve(n + 1);
    first_.push_back(0);
    std::vector<Vec3> points;
    for (std::size_t v = 0; v < n; ++v) {
        std::vector<std::uint32_t> cycle =
            links[v].size() <= kMaxNeighbours ? cycleOf(links[v]) : std::vector<std::uint32_t>{};
        points.clear();
        for (std::uint32_t w : cycle) points.push_back(soup.points[w]);
        const std::vector<Vec3> normals =
            cycle.size() >= 3 ? sectorNormalsOf(soup.points[v], points) : std::vector<Vec3>{};
        if (!normals.empty()) {
            ring_.insert(ring_.end(), cycle.begin(), cycle.end());
            sectorNormals_.insert(sectorNormals_.end(), normals.begin(), normals.end());
        }
        first_.push_back(std::uint32_t(ring_.size()));
    }
}

}  // namespace dfrecon
