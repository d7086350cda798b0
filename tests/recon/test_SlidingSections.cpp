// Sections that slide farther than their width between planes: which pairs
// are joined, how their points correspond, and a thin tilted plate against
// its exact surface.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "geometry/MeshCheck.hpp"
#include "recon/Reconstruction.hpp"
#include "recon/SlidingSections.hpp"
#include "shapes/AnalyticShapes.hpp"
#include "tests/CpuRuntime.hpp"
#include "tests/DistancesBetweenPlanes.hpp"

namespace dfrecon {
namespace {

/// A counter-clockwise rectangle (a section of a band) [x0, x0 + w] × [y0, y0 + h], 4·k points.
Polygon slidBand(double x0, double y0, double w, double h, int k = 4) {
    Polygon out;
    for (int i = 0; i < k; ++i) out.push_back({x0 + w * i / k, y0});
    for (int i = 0; i < k; ++i) out.push_back({x0 + w, y0 + h * i / k});
    for (int i = 0; i < k; ++i) out.push_back({x0 + w - w * i / k, y0 + h});
    for (int i = 0; i < k; ++i) out.push_back({x0, y0 + h - h * i / k});
    return out;
}

Polygon reversed(Polygon p) {
    std::reverse(p.begin(), p.end());
    return p;
}

/// Every contour of `layer` as one part.
LayerPart allOf(const Layer& layer) {
    LayerPart part{&layer, {}};
    for (std::uint32_t c = 0; c < layer.contours.size(); ++c) part.contours.push_back(c);
    return part;
}

}  // namespace

TEST(SlidingSections, ABandSlidPastItsWidthIsJoinedWhatIsTooFarOrTooDifferentIsNot) {
    // A band 20 × 4 mm, slid 6 mm across its width over a 5 mm slab: no
    // overlap, the same shape; joined.
    Layer lower{0, {slidBand(0, 0, 20, 4)}, {}}, upper{5, {slidBand(0, 6, 20, 4)}, {}};
    std::vector<SlidPair> pairs = matchSlidingSections(allOf(lower), allOf(upper), 5);
    ASSERT_EQ(pairs.size(), 1u);
    EXPECT_EQ(pairs[0].lower, 0u);
    EXPECT_EQ(pairs[0].upper, 0u);
    // Slid by more than twice its extent along the slide (4 mm): two specks
    // far apart for their size, not one sheet.
    upper.contours = {slidBand(0, 9, 20, 4)};
    EXPECT_TRUE(matchSlidingSections(allOf(lower), allOf(upper), 5).empty());
    // Within its extents (7.5 < 8 mm) but more than three slab heights
    // away (7.2 mm) on a thinner slab.
    upper.contours = {slidBand(0, 7.5, 20, 4)};
    EXPECT_EQ(matchSlidingSections(allOf(lower), allOf(upper), 5).size(), 1u);
    EXPECT_TRUE(matchSlidingSections(allOf(lower), allOf(upper), 2.4).empty());
    // Areas more than a factor of two apart: a rim, joined where it lies
    // within the larger section once aligned (a band 10 × 2 in the 20 × 4),
    // not where it sticks out (a band 30 × 1.2, a third of the area).
    upper.contours = {slidBand(5, 6, 10, 2)};
    EXPECT_EQ(matchSlidingSections(allOf(lower), allOf(upper), 5).size(), 1u);
    upper.contours = {slidBand(-5, 6, 30, 1.2)};
    EXPECT_TRUE(matchSlidingSections(allOf(lower), allOf(upper), 5).empty());
    // More than eight times smaller.
    upper.contours = {slidBand(8, 6, 4, 2)};
    EXPECT_TRUE(matchSlidingSections(allOf(lower), allOf(upper), 5).empty());
    // The same area, another shape: a 9 × 9 square against the band
    // overlaps it by less than half once their centroids coincide.
    upper.contours = {slidBand(5.5, 6, 9, 9)};
    EXPECT_TRUE(matchSlidingSections(allOf(lower), allOf(upper), 5).empty());
    // A ring (an ending hole inside) is left to its caps.
    upper.contours = {slidBand(0, 6, 20, 4), reversed(slidBand(5, 7, 4, 2))};
    EXPECT_TRUE(matchSlidingSections(allOf(lower), allOf(upper), 5).empty());
    // Two candidates: each joins its own best partner.
    lower.contours = {slidBand(0, 0, 20, 4), slidBand(40, 0, 10, 4)};
    upper.contours = {slidBand(40, 6, 10, 4), slidBand(0, 6, 20, 4)};
    pairs = matchSlidingSections(allOf(lower), allOf(upper), 5);
    ASSERT_EQ(pairs.size(), 2u);
    for (const SlidPair& p : pairs) EXPECT_EQ(p.upper, 1 - p.lower);
}

TEST(SlidingSections, CorrespondingPointsOfASlidCopyShareTheirParameter) {
    // The upper contour is the lower one moved, its points listed from
    // another start: each lower vertex i meets upper vertex i + 5 (mod n).
    const Polygon lower = slidBand(0, 0, 20, 4, 8);
    Polygon upper;
    const std::size_t n = lower.size();
    for (std::size_t i = 0; i < n; ++i) upper.push_back(lower[(i + 5) % n] + Point2{3, 7});
    const std::pair<AxisPositions, AxisPositions> at = slidCorrespondence(lower, upper);
    const AxisPositions &lowerAt = at.first, &upperAt = at.second;
    ASSERT_EQ(lowerAt.positions.size(), n);
    ASSERT_EQ(upperAt.positions.size(), n);
    auto upperParameter = [&](std::size_t j) {
        return upperAt.positions[(j + n - upperAt.first) % n];
    };
    for (std::size_t i = 0; i < n; ++i) {
        const double d =
            std::remainder(lowerAt.positions[i] - upperParameter((i + n - 5) % n), 1.0);
        EXPECT_NEAR(d, 0, 2e-3) << i;  // turns are tried 1/256 apart
    }
}

TEST(SlidingSections, AThinPlateLyingNearlyFlatIsJoinedWhereItsSectionsMatch) {
    // plate-20: 3 mm thick, tilted 20 degrees from the planes; at 5 mm its
    // sections slide 13.7 mm, farther than their 8.8 mm width. Joined, the
    // slab between its two large sections is the plate; capped apart, two
    // loose lids (0.86 of shape-based interpolation's slab distance; joined
    // 0.42: dfrecon-bench recon).
    const auto shape = makeShape("plate-20");
    SynthOptions slicing;
    slicing.spacingMm = 5;
    slicing.pointsPerContour = 128;
    const ContourSet set = sliceShape(*shape, slicing);
    const Roi& roi = set.rois[0];
    ReconstructionOptions apart;
    apart.joinSlidSections = false;
    const Reconstruction capped = reconstructSurface(cpuRuntime(), roi, apart);
    const Reconstruction joined = reconstructSurface(cpuRuntime(), roi);
    ASSERT_TRUE(capped.check.validSolid());
    ASSERT_TRUE(joined.check.validSolid());
    EXPECT_EQ(capped.stats.slidStrips, 0u);
    EXPECT_GE(joined.stats.slidStrips, 1u);
    // Its third section is the plate's rounded edge (38 against 371 mm2):
    // too unlike the one below to be joined, it stays a capped piece.
    EXPECT_EQ(capped.check.components, 3u);
    EXPECT_EQ(joined.check.components, 2u);
    auto meanBetweenPlanes = [&](const TriangleSoup& soup) {
        const std::vector<double> d = testing::distancesBetweenPlanes(*shape, roi, soup);
        return std::accumulate(d.begin(), d.end(), 0.0) /
               double(std::max<std::size_t>(d.size(), 1));
    };
    EXPECT_LT(meanBetweenPlanes(joined.surface), 0.7 * meanBetweenPlanes(capped.surface));
}

}  // namespace dfrecon
