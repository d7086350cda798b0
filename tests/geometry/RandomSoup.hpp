#pragma once
// Random independent triangles (no shared vertices) for BVH tests: `count`
// triangles with corners within `size` of a centre uniform in [0, extent]³.
#include <cstdint>
#include <random>

#include "geometry/TriangleSoup.hpp"

namespace dfrecon::testing {

inline TriangleSoup randomTriangles(unsigned seed, std::uint32_t count, double extent,
                                    double size) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> at(0, extent), offset(-size, size);
    TriangleSoup soup;
    for (std::uint32_t t = 0; t < count; ++t) {
        const Vec3 c{at(random), at(random), at(random)};
        for (int k = 0; k < 3; ++k)
            soup.points.push_back(c + Vec3{offset(random), offset(random), offset(random)});
        soup.triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
    }
    return soup;
}

}  // namespace dfrecon::testing
