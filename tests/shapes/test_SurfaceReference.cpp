// The reference distance for shapes whose signedDistance is a bound, against
// brute force over dense points of the surface.
#include "shapes/SurfaceReference.hpp"

#include <gtest/gtest.h>

#include <random>

#include "shapes/BetweenPlanesShapes.hpp"

using namespace dfrecon;

TEST(SurfaceReference, ExactShapesUseTheirDistance) {
    const auto sphere = makeShape("sphere");
    const SurfaceReference reference(*sphere);
    EXPECT_TRUE(reference.exact());
    EXPECT_DOUBLE_EQ(reference.distance({0, 0, 25}), 5);
    EXPECT_DOUBLE_EQ(reference.distance({0, 0, 1}), 19);
}

TEST(SurfaceReference, SmoothUnionDistanceMatchesBruteForce) {
    const auto branch = makeShape("branch");
    const SurfaceReference reference(*branch, 10000);
    EXPECT_FALSE(reference.exact());
    // Dense points exactly on the zero set, blend included (unevenly spread:
    // random points projected onto the surface reach the crotch less often).
    const std::vector<Vec3> dense = sampleSurface(*branch, 40000, 4);
    std::mt19937 random(6);
    std::uniform_int_distribution<std::size_t> pick(0, dense.size() - 1);
    std::uniform_real_distribution<double> offset(-1.5, 1.5);
    int strictlyAboveBound = 0;
    for (int trial = 0; trial < 60; ++trial) {
        const Vec3 s = dense[pick(random)];
        const Vec3 p{s.x + offset(random), s.y + offset(random), s.z + offset(random)};
        double nearest = INFINITY;
        for (const Vec3& q : dense) nearest = std::min(nearest, length(p - q));
        const Vec3 x = reference.nearestPoint(p);
        const double d = reference.distance(p);
        EXPECT_DOUBLE_EQ(d, length(p - x));
        // x is on the surface, p lies along its normal (a foot point), no
        // dense sample is nearer, and the bound is not above it.
        EXPECT_LT(std::abs(branch->signedDistance(x)), 1e-9);
        const double h = 1e-6;
        const Vec3 g{branch->signedDistance({x.x + h, x.y, x.z}) -
                         branch->signedDistance({x.x - h, x.y, x.z}),
                     branch->signedDistance({x.x, x.y + h, x.z}) -
                         branch->signedDistance({x.x, x.y - h, x.z}),
                     branch->signedDistance({x.x, x.y, x.z + h}) -
                         branch->signedDistance({x.x, x.y, x.z - h})};
        EXPECT_LT(length(cross(p - x, g)) / (length(p - x) * length(g)), 1e-5);
        EXPECT_LE(d, nearest + 1e-9);
        EXPECT_GE(d, std::abs(branch->signedDistance(p)) - 1e-9);
        if (d > std::abs(branch->signedDistance(p)) + 1e-6) ++strictlyAboveBound;
    }
    // The bound is not the distance everywhere: near the junction it is lower.
    EXPECT_GT(strictlyAboveBound, 0);
}
