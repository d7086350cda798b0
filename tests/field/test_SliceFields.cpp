// The 2D field kernel against the brute-force reference on the PoCL CPU
// device. Agreement (double precision): distance within 1e-4 px, the sign
// bit equal at every pixel (the winding numbers are the reference's exactly,
// on the contour too), and the id the kernel reports names a primitive at the
// nearest distance: the reference's own id, or within 1e-9 px of it (ties
// and near-ties resolved by rounding). Float variants get 1e-6 of the
// coordinates' size more.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "field/SliceFields.hpp"
#include "geometry/ContourValidation.hpp"
#include "shapes/AnalyticShapes.hpp"
#include "tests/CpuRuntime.hpp"

using namespace dfrecon;

namespace {

double distanceToPrimitive(Point2 p, const std::vector<Polygon>& contours, std::uint32_t id) {
    const PrimitiveId prim = PrimitiveId::decode(id);
    const Polygon& c = contours.at(prim.contour);
    const Point2 a = c.at(prim.index);
    if (prim.isVertex) return length(p - a);
    return distanceToSegment(p, a, c[(prim.index + 1) % c.size()]);
}

void expectVariantAgrees(const std::vector<Slice>& slices, const SliceGrid& grid,
                         const SliceFields& reference, const FieldKernelOptions& options) {
    const SliceFields kernel = computeSliceFields(cpuRuntime(), slices, grid, {}, options);
    ASSERT_EQ(kernel.distanceMm.size(), reference.distanceMm.size());
    const double pixel = grid.pixelMm;
    // Float carries about 1e-6 of the coordinates' magnitude on top.
    const double relative = options.singlePrecision ? 1e-6 : 0;
    int worst = 0;
    for (std::size_t s = 0; s < slices.size(); ++s)
        for (int j = 0; j < grid.height; ++j)
            for (int i = 0; i < grid.width; ++i) {
                const std::size_t k = kernel.index(s, i, j);
                const float dk = kernel.distanceMm[k], dr = reference.distanceMm[k];
                if (slices[s].contours.empty()) {
                    EXPECT_EQ(kernel.nearestId[k], kNoPrimitive);
                    continue;
                }
                const double slackPx = relative * (std::abs(dr) / pixel + grid.width + grid.height);
                const double error = std::abs(double(dk) - double(dr)) / pixel;
                if (error > 1e-4 + slackPx && worst++ < 5)
                    ADD_FAILURE() << "slice " << s << " pixel " << i << "," << j << ": " << dk
                                  << " vs " << dr;
                if (std::signbit(dk) != std::signbit(dr) && worst++ < 5)
                    ADD_FAILURE() << "sign at slice " << s << " pixel " << i << "," << j << ": "
                                  << dk << " vs " << dr;
                if (kernel.nearestId[k] == reference.nearestId[k]) continue;
                const Point2 p = grid.pixelCentre(i, j);
                const double named =
                    distanceToPrimitive(p, slices[s].contours, kernel.nearestId[k]);
                const double nearest =
                    distanceToPrimitive(p, slices[s].contours, reference.nearestId[k]);
                const double tiePx = options.singlePrecision ? 1e-5 + 2 * slackPx : 1e-9;
                if (std::abs(named - nearest) > tiePx * pixel && worst++ < 5)
                    ADD_FAILURE() << "id at slice " << s << " pixel " << i << "," << j << " names "
                                  << named << " mm away, nearest is " << nearest;
            }
    EXPECT_EQ(worst, 0);
}

// Every kernel variant: 8, 4 and 1 pixels per work-item (CPU and GPU
// shapes) in double precision, and float (devices without fp64) in 8 and 1;
// and every way to the nearest segment: every tile walking the tree per
// pixel row (lists of 0), every tile scanning its list of segments (lists
// of 4096, never of leaves), and every tile listing leaves (from 0); lanes
// along rows, columns or by the contour; tiles of 16 and 32 pixels.
void expectAgreement(const std::vector<Slice>& slices, const SliceGrid& grid) {
    const SliceFields reference = computeSliceFieldsReference(slices, grid);
    const int never = 1 << 30;
    for (const FieldKernelOptions options :
         {FieldKernelOptions{8, false},
          FieldKernelOptions{4, false},
          FieldKernelOptions{1, false},
          FieldKernelOptions{8, true},
          FieldKernelOptions{1, true},
          FieldKernelOptions{8, false, 0},
          FieldKernelOptions{1, true, 0},
          FieldKernelOptions{8, false, 4096, never},
          FieldKernelOptions{1, true, 4096, never},
          FieldKernelOptions{8, false, -1, 0},
          FieldKernelOptions{4, false, -1, 0},
          FieldKernelOptions{1, true, -1, 0},
          FieldKernelOptions{8, false, -1, -1, LanesAlong::Columns},
          FieldKernelOptions{8, false, 0, -1, LanesAlong::Columns},
          FieldKernelOptions{8, false, -1, 0, LanesAlong::Columns},
          FieldKernelOptions{1, true, -1, 0, LanesAlong::Columns},
          FieldKernelOptions{8, false, -1, 0, LanesAlong::Rows},
          FieldKernelOptions{8, false, -1, -1, LanesAlong::Contour, 16},
          FieldKernelOptions{8, false, -1, -1, LanesAlong::Contour, 32},
          FieldKernelOptions{8, false, -1, 0, LanesAlong::Contour, 32},
          FieldKernelOptions{1, true, -1, 0, LanesAlong::Contour, 32}}) {
        SCOPED_TRACE("lanes " + std::to_string(options.lanes) +
                     (options.singlePrecision ? ", float" : ", double") + ", tile lists of " +
                     std::to_string(options.tileListCapacity) + ", leaves listed from " +
                     std::to_string(options.leafListsFrom) + ", lanes along " +
                     std::to_string(int(options.lanesAlong)) + ", tiles of " +
                     std::to_string(options.tilePixels));
        expectVariantAgrees(slices, grid, reference, options);
    }
}

Polygon star(std::mt19937& random, Point2 centre, int n, double rMin, double rMax, bool ccw) {
    std::uniform_real_distribution<double> radius(rMin, rMax);
    Polygon p;
    for (int k = 0; k < n; ++k) {
        const double t = 2 * M_PI * (ccw ? k : -k) / n;
        const double r = radius(random);
        p.push_back({centre.x + r * std::cos(t), centre.y + r * std::sin(t)});
    }
    return p;
}

}  // namespace

TEST(SliceFields, RandomPolygonsWithHolesAndIslands) {
    std::mt19937 random(11);
    std::vector<Slice> slices;
    for (int s = 0; s < 6; ++s) {
        Slice slice;
        slice.zMm = s * 2.5;
        slice.contours = {star(random, {100, -50}, 40 + 13 * s, 30, 40, true),
                          star(random, {100, -50}, 25, 15, 22, false),  // hole
                          star(random, {100, -50}, 9, 4, 8, true),      // island in the hole
                          star(random, {160, -50}, 17, 6, 12, true)};   // separate blob
        ASSERT_FALSE(findContourDefect(slice.contours).has_value());
        slices.push_back(slice);
    }
    expectAgreement(slices, gridForSlices(slices, 0.7));
}

TEST(SliceFields, TouchingContoursKeepTheirSigns) {
    // Two squares meeting at a corner, and a hole touching its outer contour.
    Slice slice;
    slice.contours = {{{0, 0}, {10, 0}, {10, 10}, {0, 10}},
                      {{10, 10}, {20, 10}, {20, 20}, {10, 20}},
                      {{30, 0}, {50, 0}, {50, 20}, {30, 20}},
                      {{30, 0}, {35, 10}, {40, 5}}};
    normaliseOrientation(slice);
    const std::vector<Slice> slices{slice};
    expectAgreement(slices, gridForSlices(slices, 0.25));
    const SliceFields f = computeSliceFields(cpuRuntime(), slices, gridForSlices(slices, 0.25));
    // Just inside square 2 near the shared corner, and inside the hole.
    const SliceGrid& g = f.grid;
    const int i = int((10.3 - g.originMm.x) / g.pixelMm),
              j = int((10.3 - g.originMm.y) / g.pixelMm);
    EXPECT_LT(f.distanceMm[f.index(0, i, j)], 0);
    const int hi = int((36 - g.originMm.x) / g.pixelMm), hj = int((6 - g.originMm.y) / g.pixelMm);
    EXPECT_GT(f.distanceMm[f.index(0, hi, hj)], 0);
}

TEST(SliceFields, SpikesAndCollinearRuns) {
    Slice slice;
    Polygon spiky{{0, 0},   {5, 0},     {10, 0},  {15, 0},     {20, 0},  // collinear run
                  {20, 10}, {12, 10.2}, {10, 30}, {9.9, 10.2},           // thin spike
                  {0, 10}};
    slice.contours = {spiky};
    normaliseOrientation(slice);
    const std::vector<Slice> slices{slice};
    expectAgreement(slices, gridForSlices(slices, 0.13));
}

TEST(SliceFields, ContoursFarOutsideTheGrid) {
    Slice slice;
    slice.contours = {{{1000, 1000}, {1010, 1000}, {1005, 1008}},
                      {{-900, 0}, {-800, 0}, {-800, 50}, {-900, 50}}};
    normaliseOrientation(slice);
    SliceGrid grid;
    grid.originMm = {0, 0};
    grid.pixelMm = 1;
    grid.width = 40;
    grid.height = 33;
    expectAgreement({slice}, grid);
}

TEST(SliceFields, OneContourOfThreePointsAndEmptySlices) {
    Slice empty, triangle;
    empty.zMm = 0;
    triangle.zMm = 1;
    triangle.contours = {{{0, 0}, {4, 0}, {1, 3}}};
    const std::vector<Slice> slices{empty, triangle, empty};
    const SliceGrid grid = gridForSlices(slices, 0.05);
    expectAgreement(slices, grid);
}

TEST(SliceFields, CircleDistancesAreExactToThePolygon) {
    const ContourSet set = sliceShape(*makeShape("torus"), {});
    const std::vector<Slice>& slices = set.rois[0].slices;
    const SliceGrid grid = gridForSlices(slices, 0);
    EXPECT_LE(std::max(grid.width, grid.height), kDefaultGridPixels);
    EXPECT_GE(std::max(grid.width, grid.height), kDefaultGridPixels - 2);
    expectAgreement(slices, grid);
}

// Contours denser than the pixels (several segments per pixel), where many
// segments are nearly as near as the nearest: a jagged outline with a hole,
// an island in the hole, and a smooth circle touching nothing.
TEST(SliceFields, ContoursWithThousandsOfSegments) {
    std::mt19937 random(5);
    Slice slice;
    slice.contours = {star(random, {0, 0}, 2500, 38, 40, true),
                      star(random, {-5, 3}, 1200, 20, 21, false),
                      star(random, {-5, 3}, 400, 6, 9, true)};
    Polygon circle;
    for (int k = 0; k < 3000; ++k) {
        const double t = 2 * M_PI * k / 3000;
        circle.push_back({70 + 15 * std::cos(t), 10 + 15 * std::sin(t)});
    }
    slice.contours.push_back(circle);
    ASSERT_FALSE(findContourDefect(slice.contours).has_value());
    const std::vector<Slice> slices{slice};
    const SliceGrid grid = gridForSlices(slices, 0.9);
    expectAgreement(slices, grid);
    // The case is what it says: by default, tiles here list leaves, and
    // those where the contour runs along the rows lay their lanes down the
    // columns (the round contours run every way).
    FieldKernelStats stats;
    FieldKernelOptions options;
    options.stats = &stats;
    computeSliceFields(cpuRuntime(), slices, grid, {}, options);
    EXPECT_GT(stats.leafListingTiles, 0u);
    EXPECT_GT(stats.columnTiles, 0u);
    EXPECT_LT(stats.columnTiles, stats.leafListingTiles + stats.overflowingTiles);
    EXPECT_EQ(stats.tilePixels, 32u);  // segments far shorter than a pixel
}

// Pixel centres exactly on edges and vertices (1 mm pixels from 0: centres
// at k + 0.5): edges along rows and columns of centres, a diagonal through
// centres, a hole whose vertex touches its outer contour at a centre, two
// squares sharing a corner on a centre. Distances are 0 there and the sign is
// whatever windingNumber() says, which the kernel must match bit for bit.
TEST(SliceFields, PixelCentresOnEdgesAndVertices) {
    Slice slice;
    slice.contours = {{{2.5, 2.5}, {12.5, 2.5}, {12.5, 12.5}, {2.5, 12.5}},
                      {{12.5, 12.5}, {20.5, 12.5}, {20.5, 20.5}, {12.5, 20.5}},
                      {{24.5, 2.5}, {34.5, 12.5}, {24.5, 12.5}},
                      {{38.5, 2.5}, {50.5, 2.5}, {50.5, 14.5}, {38.5, 14.5}},
                      {{38.5, 2.5}, {44.5, 8.5}, {46.5, 4.5}}};
    normaliseOrientation(slice);
    SliceGrid grid;
    grid.originMm = {0, 0};
    grid.pixelMm = 1;
    grid.width = 56;
    grid.height = 24;
    const std::vector<Slice> slices{slice};
    expectAgreement(slices, grid);
    const SliceFields f = computeSliceFieldsReference(slices, grid);
    int onContour = 0;
    for (const float d : f.distanceMm) onContour += d == 0;
    EXPECT_GT(onContour, 80);  // the case is what it says
}

// Zero-length segments (repeated points), segments far shorter than a pixel,
// and a contour that doubles back on itself along a line.
TEST(SliceFields, DegenerateShortSegments) {
    Slice slice;
    slice.contours = {
        {{0, 0}, {0, 0}, {3, 0}, {3, 1e-9}, {3, 2e-9}, {3, 3}, {3, 3}, {3, 3}, {1e-7, 3}, {0, 3}},
        {{5, 0}, {8, 0}, {6, 0}, {9, 0}, {9, 2}, {5, 2}}};
    const std::vector<Slice> slices{slice};
    expectAgreement(slices, gridForSlices(slices, 0.11));
}

// The tile-list statistics count every tile of every slice with contours:
// all overflow with room for none, none for one small contour, whose tiles
// each list at least the segment nearest them, and all list leaves when
// told to. Lanes go down the columns of no tile that lists segments, of
// every tile when told to, and of none when told to go along the rows.
TEST(SliceFields, TileListStatsCountEveryTile) {
    Slice square, empty;
    square.contours = {{{10, 10}, {40, 10}, {40, 30}, {10, 30}}};
    const std::vector<Slice> slices{square, empty, square};
    SliceGrid grid;
    grid.originMm = {0, 0};
    grid.pixelMm = 1;
    grid.width = 100;  // 7 × 4 tiles of 16 pixels
    grid.height = 50;
    FieldKernelStats stats;
    FieldKernelOptions options;
    options.stats = &stats;
    computeSliceFields(cpuRuntime(), slices, grid, {}, options);
    EXPECT_EQ(stats.tiles, 2u * 7u * 4u);
    EXPECT_EQ(stats.tilePixels, 16u);  // sides of 20 and 30 pixels
    EXPECT_EQ(stats.overflowingTiles, 0u);
    EXPECT_GE(stats.meanListed(), 1.0);
    EXPECT_LE(stats.meanListed(), 4.0);
    options.tileListCapacity = 0;
    computeSliceFields(cpuRuntime(), slices, grid, {}, options);
    EXPECT_EQ(stats.tiles, 56u);
    EXPECT_EQ(stats.overflowingTiles, 56u);
    EXPECT_EQ(stats.meanListed(), 0.0);
    options.tileListCapacity = -1;
    options.leafListsFrom = 0;
    computeSliceFields(cpuRuntime(), slices, grid, {}, options);
    EXPECT_EQ(stats.tiles, 56u);
    EXPECT_EQ(stats.overflowingTiles, 0u);
    EXPECT_EQ(stats.leafListingTiles, 56u);
    EXPECT_EQ(stats.meanListed(), 0.0);
    // Leaf-listing tiles nearest the square's top or bottom side go down
    // their columns, those nearest its left or right side along their rows.
    EXPECT_GT(stats.columnTiles, 0u);
    EXPECT_LT(stats.columnTiles, 56u);
    options.lanesAlong = LanesAlong::Rows;
    computeSliceFields(cpuRuntime(), slices, grid, {}, options);
    EXPECT_EQ(stats.columnTiles, 0u);
    options.lanesAlong = LanesAlong::Columns;
    options.leafListsFrom = -1;
    computeSliceFields(cpuRuntime(), slices, grid, {}, options);
    EXPECT_EQ(stats.columnTiles, 56u);
    options.lanesAlong = LanesAlong::Contour;
    computeSliceFields(cpuRuntime(), slices, grid, {}, options);
    EXPECT_EQ(stats.columnTiles, 0u);
    options.tilePixels = 32;
    computeSliceFields(cpuRuntime(), slices, grid, {}, options);
    EXPECT_EQ(stats.tiles, 2u * 4u * 2u);
    EXPECT_EQ(stats.tilePixels, 32u);
    options.tilePixels = 24;
    EXPECT_THROW(computeSliceFields(cpuRuntime(), slices, grid, {}, options),
                 std::invalid_argument);
}

TEST(SliceFields, RejectsIdsThatDoNotFit) {
    Slice slice;
    slice.contours.assign(kMaxContoursPerSlice, Polygon{{0, 0}, {1, 0}, {0, 1}});
    SliceGrid grid;
    grid.width = grid.height = 4;
    EXPECT_THROW(computeSliceFieldsReference({slice}, grid), std::invalid_argument);
}

TEST(PrimitiveId, RoundTrips) {
    const PrimitiveId id{kMaxContoursPerSlice - 1, kMaxPrimitivesPerContour - 1, true};
    EXPECT_EQ(PrimitiveId::decode(id.encode()), id);
    EXPECT_NE(id.encode(), kNoPrimitive);  // the largest valid id is not the sentinel
    EXPECT_EQ(PrimitiveId::decode(PrimitiveId{3, 7, false}.encode()).index, 7u);
}

// A window is a sub-rectangle of the grid's own pixels: the kernel's values
// there are the whole grid's (to rounding of the shifted origin), so the
// reconstruction can work on one part of an ROI at the cost of its pixels.
TEST(SliceGridWindow, FieldsOnAWindowEqualTheWholeGrids) {
    std::mt19937 rng(7);
    const std::vector<Slice> slices = {
        {0.0, {star(rng, {5, 5}, 40, 4, 12, true), star(rng, {40, 10}, 30, 3, 6, true)}},
        {2.0, {star(rng, {6, 4}, 40, 4, 11, true)}}};
    const SliceGrid grid = gridForSlices(slices, 0.4);
    Box2 part;
    for (Point2 p : slices[0].contours[1]) part.add(p);
    const SliceGrid window = windowOf(grid, part, kGridMarginPx);
    ASSERT_GT(window.width, 2 * kGridMarginPx);
    ASSERT_LT(window.pixelCount(), grid.pixelCount() / 2);
    const int di = int(std::lround((window.originMm.x - grid.originMm.x) / grid.pixelMm));
    const int dj = int(std::lround((window.originMm.y - grid.originMm.y) / grid.pixelMm));
    EXPECT_NEAR(window.originMm.x, grid.originMm.x + di * grid.pixelMm, 1e-9);
    EXPECT_NEAR(window.originMm.y, grid.originMm.y + dj * grid.pixelMm, 1e-9);
    // The part's box and its margin are inside the window.
    EXPECT_LE(window.pixelCentre(kGridMarginPx, kGridMarginPx).x, part.min.x);
    EXPECT_LE(window.pixelCentre(kGridMarginPx, kGridMarginPx).y, part.min.y);
    EXPECT_GE(window.pixelCentre(window.width - 1 - kGridMarginPx, 0).x, part.max.x);
    EXPECT_GE(window.pixelCentre(0, window.height - 1 - kGridMarginPx).y, part.max.y);

    const SliceFields whole = computeSliceFields(cpuRuntime(), slices, grid);
    const SliceFields part2 = computeSliceFields(cpuRuntime(), slices, window);
    for (std::size_t s = 0; s < slices.size(); ++s)
        for (int j = 0; j < window.height; ++j)
            for (int i = 0; i < window.width; ++i) {
                const float a = part2.distanceMm[part2.index(s, i, j)];
                const float b = whole.distanceMm[whole.index(s, i + di, j + dj)];
                ASSERT_NEAR(a, b, 1e-5 * grid.pixelMm) << s << " " << i << "," << j;
            }
    // Clipped to the grid, and empty for an empty box.
    Box2 beyond;
    beyond.add({-1e3, -1e3});
    beyond.add({1e3, 1e3});
    const SliceGrid all = windowOf(grid, beyond, kGridMarginPx);
    EXPECT_EQ(all.width, grid.width);
    EXPECT_EQ(all.height, grid.height);
    EXPECT_EQ(windowOf(grid, Box2{}, kGridMarginPx).pixelCount(), 0u);
}
