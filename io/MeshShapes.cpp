#include "io/MeshShapes.hpp"

#include <cmath>
#include <map>
#include <utility>

namespace dfrecon {

TriangleSoup icosphere(Vec3 centre, double radiusMm, int subdivisions) {
    const double g = (1 + std::sqrt(5.0)) / 2;
    std::vector<Vec3> unit = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                              {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                              {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    for (Vec3& p : unit) p = (1 / length(p)) * p;
    std::vector<std::array<std::uint32_t, 3>> faces = {
        {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int s = 0; s < subdivisions; ++s) {
        // Edge midpoints shared by both triangles of an edge keep it closed.
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoint;
        auto middle = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::make_pair(std::min(a, b), std::max(a, b));
            const auto found = midpoint.find(key);
            if (found != midpoint.end()) return found->second;
            const Vec3 m = 0.5 * (unit[a] + unit[b]);
            unit.push_back((1 / length(m)) * m);
            return midpoint[key] = std::uint32_t(unit.size() - 1);
        };
        std::vector<std::array<std::uint32_t, 3>> finer;
        for (const auto& f : faces) {
            const std::uint32_t ab = middle(f[0], f[1]), bc = middle(f[1], f[2]),
                                ca = middle(f[2], f[0]);
            finer.push_back({f[0], ab, ca});
            finer.push_back({f[1], bc, ab});
            finer.push_back({f[2], ca, bc});
            finer.push_back({ab, bc, ca});
        }
        faces = std::move(finer);
    }
    TriangleSoup soup;
    for (const Vec3& p : unit) soup.points.push_back(centre + radiusMm * p);
    soup.triangles = std::move(faces);
    return soup;
}

TriangleSoup boxMesh(Vec3 lo, Vec3 hi, int n) {
    TriangleSoup soup;
    std::map<std::array<long, 3>, std::uint32_t> index;  // grid corner → point
    auto point = [&](long i, long j, long k) {
        const std::array<long, 3> key{i, j, k};
        const auto found = index.find(key);
        if (found != index.end()) return found->second;
        soup.points.push_back({lo.x + (hi.x - lo.x) * double(i) / n,
                               lo.y + (hi.y - lo.y) * double(j) / n,
                               lo.z + (hi.z - lo.z) * double(k) / n});
        return index[key] = std::uint32_t(soup.points.size() - 1);
    };
    // Each face: a fixed axis at 0 or n, two running axes (u, v) ordered so
    // that u × v points out of the box.
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            for (long a = 0; a < n; ++a)
                for (long b = 0; b < n; ++b) {
                    std::array<std::uint32_t, 4> q;
                    const long corners[4][2] = {{a, b}, {a + 1, b}, {a + 1, b + 1}, {a, b + 1}};
                    for (int c = 0; c < 4; ++c) {
                        std::array<long, 3> ijk{};
                        ijk[std::size_t(axis)] = side * n;
                        ijk[std::size_t(u)] = corners[c][0];
                        ijk[std::size_t(v)] = corners[c][1];
                        q[std::size_t(c)] = point(ijk[0], ijk[1], ijk[2]);
                    }
                    if (side == 1) {
                        soup.triangles.push_back({q[0], q[1], q[2]});
                        soup.triangles.push_back({q[0], q[2], q[3]});
                    } else {
                        soup.triangles.push_back({q[0], q[2], q[1]});
                        soup.triangles.push_back({q[0], q[3], q[2]});
                    }
                }
        }
    return soup;
}

}  // namespace dfrecon
