// Sections traced from a distance against sections known in closed form.
#include "shapes/ImplicitSection.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace dfrecon;

namespace {

double sphere(Vec3 p, Vec3 c, double r) {
    return length(p - c) - r;
}

Box2 box(double half) {
    return {{-half, -half}, {half, half}};
}

}  // namespace

TEST(ImplicitSection, SphereGivesACircleWithEvenlySpacedVerticesOnIt) {
    const auto f = [](Vec3 p) { return sphere(p, {1, 2, 0}, 10); };
    const std::vector<Polygon> section = implicitSection(f, box(20), 6, 0.05, 64);
    ASSERT_EQ(section.size(), 1u);
    ASSERT_EQ(section[0].size(), 64u);
    double shortest = INFINITY, longest = 0;
    for (std::size_t k = 0; k < 64; ++k) {
        const Point2 p = section[0][k], q = section[0][(k + 1) % 64];
        EXPECT_NEAR(length(p - Point2{1, 2}), 8, 1e-12);
        shortest = std::min(shortest, length(q - p));
        longest = std::max(longest, length(q - p));
    }
    EXPECT_LT(longest - shortest, 0.1);  // even to about a cell
    EXPECT_NEAR(std::abs(signedArea(section[0])), 64 * 32 * std::sin(2 * M_PI / 64), 1.0);
}

TEST(ImplicitSection, SeparateAndNestedContours) {
    // Two balls: two circles. A hollow ball: a circle inside a circle.
    const auto two = [](Vec3 p) {
        return std::min(sphere(p, {-8, 0, 0}, 5), sphere(p, {8, 0, 0}, 5));
    };
    EXPECT_EQ(implicitSection(two, box(20), 0, 0.05, 32).size(), 2u);
    const auto hollow = [](Vec3 p) { return std::max(length(p) - 10, 6 - length(p)); };
    const std::vector<Polygon> ring = implicitSection(hollow, box(20), 1, 0.05, 32);
    ASSERT_EQ(ring.size(), 2u);
    const double r0 = length(ring[0][0]), r1 = length(ring[1][0]);
    EXPECT_NEAR(std::min(r0, r1), std::sqrt(35.0), 1e-12);
    EXPECT_NEAR(std::max(r0, r1), std::sqrt(99.0), 1e-12);
}

TEST(ImplicitSection, FewerCrossingsThanPointsKeepsThemAll) {
    const auto f = [](Vec3 p) { return sphere(p, {}, 1); };
    const std::vector<Polygon> section = implicitSection(f, box(2), 0, 0.25, 1000);
    ASSERT_EQ(section.size(), 1u);
    EXPECT_LT(section[0].size(), 40u);
    EXPECT_GE(section[0].size(), 16u);
    for (Point2 p : section[0]) EXPECT_NEAR(length(p), 1, 1e-12);
}

TEST(ImplicitSection, NothingOutsideTheSolid) {
    const auto f = [](Vec3 p) { return sphere(p, {}, 5); };
    EXPECT_TRUE(implicitSection(f, box(10), 5.01, 0.05, 32).empty());
    EXPECT_TRUE(implicitSection(f, Box2{}, 0, 0.05, 32).empty());
}
