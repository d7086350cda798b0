// The generated meshes against their exact properties: counts, closedness
// and orientation (the mesh checker, geometry/MeshCheck), radius, area, volume and angles.
#include "shapes/MeshShapes.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/MeshCheck.hpp"

using namespace dfrecon;

namespace {

double largestAngleDeg(const TriangleSoup& soup) {
    double largest = 0;
    for (const auto& tri : soup.triangles)
        for (int k = 0; k < 3; ++k) {
            const Vec3 c = soup.points[tri[std::size_t(k)]];
            const Vec3 a = soup.points[tri[std::size_t((k + 1) % 3)]] - c;
            const Vec3 b = soup.points[tri[std::size_t((k + 2) % 3)]] - c;
            largest = std::max(largest, std::acos(dot(a, b) / (length(a) * length(b))));
        }
    return largest * 180 / M_PI;
}

}  // namespace

TEST(MeshShapes, GeodesicSphereIsAClosedSphereOfAcuteTriangles) {
    for (int f : {1, 2, 5, 16}) {
        const TriangleSoup sphere = geodesicSphere(f, 2.0);
        const MeshCheckReport check = checkMesh(sphere);
        EXPECT_EQ(check.vertices, std::size_t(10 * f * f + 2));
        EXPECT_EQ(check.triangles, std::size_t(20 * f * f));
        EXPECT_TRUE(check.validSolid());  // closed, oriented, outward (positive volume)
        for (const Vec3& p : sphere.points) EXPECT_NEAR(length(p), 2.0, 1e-12);
        EXPECT_LT(largestAngleDeg(sphere), 90.0);
    }
}

TEST(MeshShapes, BoxesAreClosedWithExactAreaAndVolume) {
    const MeshCheckReport cube = checkMesh(tessellatedCube(5, 2.0));
    EXPECT_EQ(cube.vertices, std::size_t(6 * 25 + 2));
    EXPECT_TRUE(cube.validSolid());
    EXPECT_NEAR(cube.areaMm2, 24.0, 1e-12);
    EXPECT_NEAR(cube.volumeMm3, 8.0, 1e-12);
    const MeshCheckReport box = checkMesh(boxMesh({1, 2, 3}, {4, 6, 8}, 3));
    EXPECT_EQ(box.triangles, std::size_t(12 * 9));
    EXPECT_TRUE(box.validSolid());
    EXPECT_NEAR(box.areaMm2, 2 * (3 * 4 + 4 * 5 + 3 * 5), 1e-9);
    EXPECT_NEAR(box.volumeMm3, 3 * 4 * 5, 1e-9);
}

TEST(MeshShapes, StaggeredGridIsObtuseWhenFlat) {
    const TriangleSoup flat = staggeredGrid(10, 10, 1.0, 0.2);
    EXPECT_NEAR(largestAngleDeg(flat), 2 * std::atan(2.5) * 180 / M_PI, 1e-9);
    EXPECT_NEAR(checkMesh(flat).areaMm2, 10 * 10 * 0.2, 1e-9);
    EXPECT_NEAR(largestAngleDeg(staggeredGrid(6, 6, 1.0, std::sqrt(0.75))), 60.0, 1e-9);
}
