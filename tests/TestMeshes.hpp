#pragma once
// Closed triangle meshes the tests build by formula.
#include <cmath>
#include <cstdint>

#include "geometry/TriangleSoup.hpp"

namespace dfrecon::testing {

/// A torus around the z axis (major radius R, tube radius r) as an n × m
/// grid of quads, each cut in two; outward, closed, genus 1.
inline TriangleSoup torusMesh(double R, double r, int n, int m) {
    constexpr double kPi = 3.14159265358979323846;
    TriangleSoup s;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j) {
            const double u = 2 * kPi * i / n, v = 2 * kPi * j / m;
            s.points.push_back({(R + r * std::cos(v)) * std::cos(u),
                                (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
        }
    auto at = [&](int i, int j) { return std::uint32_t(((i + n) % n) * m + (j + m) % m); };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j) {
            s.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            s.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return s;
}

}  // namespace dfrecon::testing
