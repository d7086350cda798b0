#include "shapes/MeshShapes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace dfrecon {

TriangleSoup geodesicSphere(int frequency, double radius, Vec3 centre) {
    if (frequency < 1) throw std::invalid_argument("geodesicSphere: frequency < 1");
    const double phi = (1 + std::sqrt(5.0)) / 2;
    const std::array<Vec3, 12> corners{{{-1, phi, 0},
                                        {1, phi, 0},
                                        {-1, -phi, 0},
                                        {1, -phi, 0},
                                        {0, -1, phi},
                                        {0, 1, phi},
                                        {0, -1, -phi},
                                        {0, 1, -phi},
                                        {phi, 0, -1},
                                        {phi, 0, 1},
                                        {-phi, 0, -1},
                                        {-phi, 0, 1}}};
    const std::array<std::array<int, 3>, 20> faces{
        {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
         {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
         {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}}};
    const int n = frequency;
    TriangleSoup soup;
    // A point is the combination Σ w_i corner_i / n of at most three
    // icosahedron corners; points on shared edges are keyed by their sorted
    // (corner, weight) pairs so that every face finds the same one, and are
    // computed from that sorted combination so that they are bit-identical.
    std::unordered_map<std::uint64_t, std::uint32_t> shared;
    const auto pointIndex = [&](std::array<std::pair<int, int>, 3> terms) {
        std::sort(terms.begin(), terms.end());
        Vec3 p{};
        std::uint64_t key = 0;
        int used = 0;
        for (const auto& [corner, weight] : terms) {
            if (weight == 0) continue;
            p = p + (double(weight) / n) * corners[std::size_t(corner)];
            key = key << 24 | std::uint64_t(corner) << 20 | std::uint64_t(weight);
            ++used;
        }
        const auto make = [&] {
            soup.points.push_back(centre + (radius / length(p)) * p);
            return std::uint32_t(soup.points.size() - 1);
        };
        if (used == 3) return make();  // inside a face: nobody else has it
        auto [it, inserted] = shared.try_emplace(key, 0);
        if (inserted) it->second = make();
        return it->second;
    };
    for (const auto& f : faces) {
        std::vector<std::uint32_t> grid;  // (i, j) with i + j ≤ n, row by row
        std::vector<std::size_t> rowStart;
        for (int i = 0; i <= n; ++i) {
            rowStart.push_back(grid.size());
            for (int j = 0; i + j <= n; ++j)
                grid.push_back(pointIndex({{{f[0], n - i - j}, {f[1], i}, {f[2], j}}}));
        }
        const auto at = [&](int i, int j) {
            return grid[rowStart[std::size_t(i)] + std::size_t(j)];
        };
        for (int i = 0; i < n; ++i)
            for (int j = 0; i + j < n; ++j) {
                soup.triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
                if (i + j + 1 < n)
                    soup.triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
            }
    }
    return soup;
}

TriangleSoup jitteredGeodesicSphere(int frequency, double jitter, unsigned seed, double radius) {
    TriangleSoup soup = geodesicSphere(frequency, radius);
    // The icosahedron's edge is 1.05 radii; the sphere's edges about that / frequency.
    const double edge = 1.1 * radius / frequency;
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> offset(-jitter * edge, jitter * edge);
    for (Vec3& p : soup.points) {
        p = p + Vec3{offset(random), offset(random), offset(random)};
        p = (radius / length(p)) * p;
    }
    return soup;
}

TriangleSoup tessellatedCube(int n, double size) {
    if (n < 1) throw std::invalid_argument("tessellatedCube: n < 1");
    return boxMesh({-0.5 * size, -0.5 * size, -0.5 * size}, {0.5 * size, 0.5 * size, 0.5 * size},
                   n);
}

TriangleSoup staggeredGrid(int columns, int rows, double dx, double dy) {
    if (columns < 1 || rows < 1) throw std::invalid_argument("staggeredGrid: empty grid");
    TriangleSoup soup;
    const auto at = [columns](int i, int j) { return std::uint32_t(j * (columns + 1) + i); };
    for (int j = 0; j <= rows; ++j)
        for (int i = 0; i <= columns; ++i)
            soup.points.push_back({i * dx + (j % 2 ? dx / 2 : 0.0), j * dy, 0});
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i) {
            if (j % 2 == 0) {  // upper row shifted right
                soup.triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
                soup.triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
            } else {  // this row shifted right
                soup.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
                soup.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            }
        }
    return soup;
}

TriangleSoup squareGrid(int columns, int rows, double spacing) {
    if (columns < 1 || rows < 1) throw std::invalid_argument("squareGrid: empty grid");
    TriangleSoup soup;
    const auto at = [columns](int i, int j) { return std::uint32_t(j * (columns + 1) + i); };
    for (int j = 0; j <= rows; ++j)
        for (int i = 0; i <= columns; ++i) soup.points.push_back({i * spacing, j * spacing, 0});
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i) {
            soup.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            soup.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
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
