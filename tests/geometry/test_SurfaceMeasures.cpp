// Enclosed volume, area and the volume below a plane against exact values.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "geometry/SurfaceMeasures.hpp"

namespace dfrecon {
namespace {

// The tetrahedron with corners at the origin and the three unit points,
// outward-oriented.
TriangleSoup unitTetrahedron() {
    TriangleSoup soup;
    soup.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    soup.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    return soup;
}

}  // namespace

TEST(SurfaceMeasures, VolumeAndAreaOfATetrahedron) {
    const SurfaceMeasures m = measureSurface(unitTetrahedron());
    EXPECT_NEAR(m.volumeMm3, 1.0 / 6, 1e-15);
    EXPECT_NEAR(m.areaMm2, 1.5 + std::sqrt(3.0) / 2, 1e-15);
}

TEST(SurfaceMeasures, VolumeBelowAPlaneIsTheExactSlice) {
    // Below z = c the tetrahedron holds 1/6 − (1 − c)³/6: every plane cuts
    // three of its faces through their interior, tilted and flat alike.
    const TriangleSoup tet = unitTetrahedron();
    for (double c : {-0.5, 0.0, 0.1, 0.37, 0.5, 0.93, 1.0, 2.0}) {
        const double kept = std::clamp(c, 0.0, 1.0);
        const double exact = 1.0 / 6 - std::pow(1 - kept, 3) / 6;
        EXPECT_NEAR(volumeBelowPlane(tet, c), exact, 1e-15) << c;
    }
    // Moved and turned upside down (z → 5 − z): the part below is the
    // complement.
    TriangleSoup flipped = tet;
    for (Vec3& p : flipped.points) p = {p.x, -p.y, 5 - p.z};
    for (double c : {4.2, 4.5, 4.9})
        EXPECT_NEAR(volumeBelowPlane(flipped, c), std::pow(c - 4, 3) / 6, 1e-14) << c;
}

}  // namespace dfrecon
