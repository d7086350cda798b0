// Vertex fans: the ring around each vertex in order, sectors that tile
// space, and the fans refused because their sectors could not.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <vector>

#include "geometry/VertexFans.hpp"

using namespace dfrecon;

namespace {

// A closed torus (radii 10 and 4 mm) of n × m quads, each split in two
// triangles oriented outwards: convex and saddle-shaped vertices alike.
TriangleSoup torus(std::uint32_t n, std::uint32_t m) {
    TriangleSoup soup;
    for (std::uint32_t i = 0; i < n; ++i)
        for (std::uint32_t j = 0; j < m; ++j) {
            const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
            soup.points.push_back({(10 + 4 * std::cos(v)) * std::cos(u),
                                   (10 + 4 * std::cos(v)) * std::sin(u), 4 * std::sin(v)});
        }
    auto at = [&](std::uint32_t i, std::uint32_t j) { return (i % n) * m + j % m; };
    for (std::uint32_t i = 0; i < n; ++i)
        for (std::uint32_t j = 0; j < m; ++j) {
            soup.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            soup.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return soup;
}

// A fan around the origin: neighbours at these angles (degrees) in the
// plane z = 0, lifted by `lift` each, one triangle (0, k, k + 1) per step.
TriangleSoup fan(const std::vector<double>& degrees, const std::vector<double>& lift,
                 bool closed = true) {
    TriangleSoup soup;
    soup.points.push_back({0, 0, 0});
    for (std::size_t k = 0; k < degrees.size(); ++k) {
        const double a = degrees[k] * M_PI / 180;
        soup.points.push_back({std::cos(a), std::sin(a), lift.empty() ? 0 : lift[k]});
    }
    const std::uint32_t m = std::uint32_t(degrees.size());
    for (std::uint32_t k = 0; k < (closed ? m : m - 1); ++k)
        soup.triangles.push_back({0, 1 + k, 1 + (k + 1) % m});
    return soup;
}

}  // namespace

TEST(VertexFans, EveryTorusVertexHasItsTrianglesInOrder) {
    const TriangleSoup soup = torus(24, 12);
    const VertexFans fans(soup);
    std::set<std::array<std::uint32_t, 3>> triangles;
    for (const auto& t : soup.triangles) {
        // Each triangle under all three rotations of its corners.
        triangles.insert({t[0], t[1], t[2]});
        triangles.insert({t[1], t[2], t[0]});
        triangles.insert({t[2], t[0], t[1]});
    }
    for (std::uint32_t v = 0; v < soup.points.size(); ++v) {
        ASSERT_EQ(fans.neighbours(v), 6u) << "vertex " << v;
        const std::uint32_t first = fans.first()[v];
        for (std::uint32_t i = 0; i < 6; ++i) {
            const std::uint32_t w = fans.ring()[first + i], next = fans.ring()[first + (i + 1) % 6];
            EXPECT_TRUE(triangles.count({v, w, next})) << "vertex " << v << ", step " << i;
        }
    }
}

// Every point near a vertex lies in at least one sector of its fan: the
// sectors cover space, so the fan rule misses no part of a piece.
TEST(VertexFans, SectorsCoverSpaceAroundEveryVertex) {
    const TriangleSoup soup = torus(16, 8);
    const VertexFans fans(soup);
    std::mt19937 random(3);
    std::uniform_real_distribution<double> offset(-3, 3);
    for (std::uint32_t v = 0; v < soup.points.size(); ++v) {
        const std::uint32_t first = fans.first()[v], m = std::uint32_t(fans.neighbours(v));
        ASSERT_GE(m, 3u);
        for (int trial = 0; trial < 200; ++trial) {
            const Vec3 x = Vec3{offset(random), offset(random), offset(random)};
            int inside = 0;
            for (std::uint32_t i = 0; i < m; ++i) {
                const Vec3 ni = fans.sectorNormals()[first + i];
                const Vec3 nj = fans.sectorNormals()[first + (i + 1) % m];
                inside += dot(x, ni) >= 0 && dot(x, nj) <= 0;
            }
            EXPECT_EQ(inside, 1) << "vertex " << v << ", offset " << x.x << " " << x.y << " "
                                 << x.z;
        }
    }
}

TEST(VertexFans, RefusesFansWhoseSectorsCannotTile) {
    // A flat hexagon and a cone: fans.
    EXPECT_EQ(VertexFans(fan({0, 60, 120, 180, 240, 300}, {})).neighbours(0), 6u);
    EXPECT_EQ(VertexFans(fan({0, 60, 120, 180, 240, 300}, {1, 1, 1, 1, 1, 1})).neighbours(0), 6u);
    // Open (a boundary vertex): no fan.
    EXPECT_EQ(VertexFans(fan({0, 60, 120, 180, 240, 300}, {}, false)).neighbours(0), 0u);
    // A step of more than 180°: the vertex outside its ring (a sharp ridge
    // seen from above), the sectors not convex.
    EXPECT_EQ(VertexFans(fan({0, 20, 40, 60}, {})).neighbours(0), 0u);
    // Twice around: a fan wound two turns.
    std::vector<double> twice;
    for (int k = 0; k < 10; ++k) twice.push_back(72.0 * k);
    EXPECT_EQ(VertexFans(fan(twice, {})).neighbours(0), 0u);
    // More neighbours than the kernel's fixed arrays take.
    std::vector<double> many;
    for (int k = 0; k < 17; ++k) many.push_back(360.0 * k / 17);
    EXPECT_EQ(VertexFans(fan(many, {})).neighbours(0), 0u);
    many.pop_back();
    for (double& a : many) a = a * 17 / 16;
    EXPECT_EQ(VertexFans(fan(many, {})).neighbours(0), 16u);
    // Two fans touching at one vertex (a bow tie): neither cycle is its fan.
    TriangleSoup bowTie = fan({0, 60, 120}, {});
    const TriangleSoup other = fan({180, 240, 300}, {});
    for (std::size_t k = 1; k < other.points.size(); ++k) bowTie.points.push_back(other.points[k]);
    for (auto t : other.triangles) {
        for (auto& i : t)
            if (i > 0) i += 3;
        bowTie.triangles.push_back(t);
    }
    EXPECT_EQ(VertexFans(bowTie).neighbours(0), 0u);
}
