// Opening touch points between contours of one plane: afterwards no contour
// touches or crosses another, the opened points moved by at most the gap,
// and every other point stayed where it was.
#include <gtest/gtest.h>

#include <algorithm>

#include "geometry/ContourValidation.hpp"
#include "geometry/TouchSeparation.hpp"

namespace dfrecon {
namespace {

constexpr double kGap = 2e-3;

Polygon square(double x0, double y0, double side, bool clockwise = false) {
    Polygon p{{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}};
    if (clockwise) std::reverse(p.begin(), p.end());
    return p;
}

// Every point of `after` is within `gap` of a point or edge of `before`, and
// all but `moved` of them are points of `before` exactly.
void expectSmallChange(const std::vector<Polygon>& before, const std::vector<Polygon>& after,
                       std::size_t moved) {
    ASSERT_EQ(before.size(), after.size());
    std::size_t changed = 0;
    for (std::size_t c = 0; c < before.size(); ++c)
        for (Point2 p : after[c]) {
            const bool kept = std::find(before[c].begin(), before[c].end(), p) != before[c].end();
            if (!kept) ++changed;
            EXPECT_LE(distanceToBoundary(p, before[c]), kGap) << "contour " << c;
        }
    EXPECT_EQ(changed, moved);
}

void expectApart(const std::vector<Polygon>& contours) {
    EXPECT_TRUE(findContourTouches(contours).empty());
    EXPECT_FALSE(findContourDefect(contours).has_value());
}

TEST(TouchSeparation, SquaresTouchingAtACornerComeApart) {
    const std::vector<Polygon> before{square(0, 0, 1), square(1, 1, 1)};
    std::vector<Polygon> after = before;
    EXPECT_EQ(separateTouchingContours(after, kGap), 1u);
    expectApart(after);
    expectSmallChange(before, after, 2);
    // Siblings shrink: each moved corner went into its own square.
    EXPECT_LT(signedArea(after[0]), 1);
    EXPECT_LT(signedArea(after[1]), 1);
}

TEST(TouchSeparation, ACornerOnAnEdgeGetsAVertexThere) {
    const Polygon triangle{{0.5, 1}, {1.5, 2}, {-0.5, 2}};
    const std::vector<Polygon> before{square(0, 0, 1), triangle};
    std::vector<Polygon> after = before;
    EXPECT_EQ(separateTouchingContours(after, kGap), 1u);
    expectApart(after);
    EXPECT_EQ(after[0].size(), 5u);  // the square got the touch point, moved inside
    EXPECT_LT(after[0][3].y, 1);
}

TEST(TouchSeparation, AHoleTouchingItsOutlineMovesInward) {
    // A diamond hole whose right corner lies on the outline's right edge.
    const Polygon hole{{4, 2}, {3, 1}, {2, 2}, {3, 3}};
    const std::vector<Polygon> before{square(0, 0, 4), hole};
    std::vector<Polygon> after = before;
    EXPECT_EQ(separateTouchingContours(after, kGap), 1u);
    expectApart(after);
    for (Point2 p : after[1]) EXPECT_NE(windingNumber(p, after[0]), 0) << p.x << " " << p.y;
    // The ring between them widened: the outline grew, the hole shrank.
    EXPECT_GT(signedArea(after[0]), 16);
    EXPECT_GT(signedArea(after[1]), signedArea(hole));  // clockwise: less negative
}

TEST(TouchSeparation, ADiagonalChainOfPixelsComesApartEverywhere) {
    // Five pixels in an X, as a 4-connected mask tracer would outline them:
    // the centre one touches each of the four others at a corner.
    std::vector<Polygon> before;
    for (const auto& [x, y] : {std::pair{1, 1}, {0, 0}, {2, 0}, {0, 2}, {2, 2}})
        before.push_back(square(x, y, 1));
    std::vector<Polygon> after = before;
    EXPECT_EQ(separateTouchingContours(after, kGap), 4u);
    expectApart(after);
    expectSmallChange(before, after, 8);
}

TEST(TouchSeparation, ContoursThatDoNotTouchStayAsTheyAre) {
    const std::vector<Polygon> before{square(0, 0, 1), square(2, 0, 1), square(-2, -2, 6, true)};
    std::vector<Polygon> after = before;
    EXPECT_EQ(separateTouchingContours(after, kGap), 0u);
    EXPECT_EQ(after, before);
}

}  // namespace
}  // namespace dfrecon
