// A part built apart (recon/SurfaceBuilder takePart/appendPart) goes without
// the new points no triangle uses, and appended it names the same positions
// as the builder that made it: checked corner by corner against the part's
// own builder before it was taken.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "recon/SurfaceBuilder.hpp"

namespace dfrecon {
namespace {

using Corners = std::array<Vec3, 3>;

std::vector<Corners> cornersOf(const TriangleSoup& soup, std::size_t first = 0) {
    std::vector<Corners> corners;
    for (std::size_t t = first; t < soup.triangles.size(); ++t) {
        const auto& tri = soup.triangles[t];
        corners.push_back({soup.points[tri[0]], soup.points[tri[1]], soup.points[tri[2]]});
    }
    return corners;
}

bool samePoint(const Vec3& a, const Vec3& b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

TEST(SurfaceBuilder, TakePartDropsUnusedNewPointsAndKeepsTheRest) {
    const std::vector<Vec3> shared{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    SurfaceBuilder slab(shared);
    slab.setPiece(3);
    slab.addVertex({5, 5}, 1);  // no triangle uses it
    const std::uint32_t a = slab.addVertex({0.5, 0.5}, 1);
    slab.addVertex({6, 6}, 1);  // nor this one
    const std::uint32_t b = slab.addVertex({0.25, 0.75}, 1);
    slab.addTriangle(0, 1, a);
    slab.addTriangle(a, 2, b);
    slab.addTriangle(b, 3, 1);
    slab.markLoftSince(1);
    const std::vector<Corners> made = cornersOf(slab.soup());

    SurfacePart part = slab.takePart(shared.size());
    ASSERT_EQ(part.points.size(), 2u);  // a and b, in that order
    EXPECT_TRUE(samePoint(part.points[0], Vec3{0.5, 0.5, 1}));
    EXPECT_TRUE(samePoint(part.points[1], Vec3{0.25, 0.75, 1}));
    EXPECT_EQ(part.pieces, (std::vector<std::uint32_t>{3, 3, 3}));
    EXPECT_EQ(part.lofts, (std::vector<bool>{false, true, true}));
    EXPECT_EQ(slab.soup().points.size(), shared.size());
    EXPECT_EQ(slab.triangleCount(), 0u);

    // Appended after another part's points: the ids move, the corners not.
    SurfaceBuilder whole(shared);
    whole.addVertex({9, 9}, 2);
    whole.addTriangle(0, 1, 4);
    const std::size_t before = whole.triangleCount();
    whole.appendPart(std::move(part));
    const std::vector<Corners> appended = cornersOf(whole.soup(), before);
    ASSERT_EQ(appended.size(), made.size());
    for (std::size_t t = 0; t < made.size(); ++t)
        for (std::size_t k = 0; k < 3; ++k)
            EXPECT_TRUE(samePoint(appended[t][k], made[t][k]))
                << "triangle " << t << " corner " << k;
    EXPECT_EQ(whole.soup().points.size(), shared.size() + 1 + 2);
}

}  // namespace
}  // namespace dfrecon
