// The reconstruction end to end: every result is checked by the mesh checker
// (closed, manifold, oriented, no self-intersections), against the expected
// topology, and against exact volumes or analytic surfaces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

#include "field/Rasterization.hpp"
#include "geometry/MeshCheck.hpp"
#include "geometry/SurfaceMeasures.hpp"
#include "io/contours/SlicesFile.hpp"
#include "recon/Reconstruction.hpp"
#include "shapes/AnalyticShapes.hpp"
#include "tests/CpuRuntime.hpp"

namespace dfrecon {
namespace {

Polygon circle(Point2 centre, double radius) {
    return circlePolygon(centre, radius, 48);
}

Polygon squareContour(double x0, double y0, double side) {
    return {{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}};
}

Roi stack(const std::vector<std::vector<Polygon>>& slices, double spacingMm = 2) {
    Roi roi;
    roi.name = "test";
    for (std::size_t s = 0; s < slices.size(); ++s) {
        Slice slice{spacingMm * double(s), slices[s]};
        normaliseOrientation(slice);
        roi.slices.push_back(slice);
    }
    return roi;
}

struct Checked {
    Reconstruction result;
    MeshCheckReport check;
};

Checked reconstruct(const Roi& roi, const ReconstructionOptions& options = {}) {
    Checked c;
    c.result = reconstructSurface(cpuRuntime(), roi, options);
    c.check = checkMesh(c.result.surface);
    return c;
}

void expectSolid(const Checked& c, long genus, std::size_t components) {
    EXPECT_TRUE(c.check.watertight())
        << "boundary " << c.check.boundaryEdges << " non-manifold " << c.check.nonManifoldEdges
        << "/" << c.check.nonManifoldVertices << " misoriented " << c.check.misorientedEdges
        << " degenerate " << c.check.degenerateTriangles;
    EXPECT_EQ(c.check.intersectingPairs, 0u);
    EXPECT_GT(c.check.volumeMm3, 0) << "normals point outward";
    EXPECT_EQ(c.check.genus, genus);
    EXPECT_EQ(c.check.components, components);
}

// Every contour point is a vertex of the surface, exactly as a float mesh
// file holds it (the surface is checked, and so given, in floats).
void expectContoursAreVertices(const Roi& roi, const TriangleSoup& surface) {
    std::set<std::tuple<double, double, double>> vertices;
    for (const Vec3& p : surface.points) vertices.insert({p.x, p.y, p.z});
    for (const Slice& slice : roi.slices)
        for (const Polygon& contour : slice.contours)
            for (Point2 p : contour)
                ASSERT_TRUE(vertices.count(
                    {double(float(p.x)), double(float(p.y)), double(float(slice.zMm))}))
                    << p.x << " " << p.y << " " << slice.zMm;
}

TEST(Reconstruction, EverySynthShapeIsAValidSolidOfTheRightTopology) {
    for (const std::string& name : shapeNames())
        for (double spacing : {2.0, 5.0}) {
            SCOPED_TRACE(name + " at " + std::to_string(spacing) + " mm");
            const auto shape = makeShape(name);
            SynthOptions options;
            options.spacingMm = spacing;
            const ContourSet set = sliceShape(*shape, options);
            const Roi& roi = set.rois[0];
            const Checked c = reconstruct(roi);
            const std::size_t components = name == "two-blobs" || name == "hollow-sphere"   ? 2
                                           : name == "shell-island" || name == "shell-pole" ? 3
                                                                                            : 1;
            expectSolid(c, name == "torus" ? 1 : 0, components);
            expectContoursAreVertices(roi, c.result.surface);
            EXPECT_NEAR(c.check.volumeMm3 / shape->volumeMm3(), 1.0, spacing < 3 ? 0.02 : 0.05);
            // Nothing strays further from the true surface than the slices
            // leave undetermined.
            for (const Vec3& p : c.result.surface.points)
                ASSERT_LT(std::abs(shape->signedDistance(p)), 0.6 * spacing);
        }
}

// Every contour point is a vertex on every shape there is (the between-planes
// family too), at both spacings, in both interpolations and both closed cap
// modes, and with noisy contours: the construction keeps them (contour
// vertices are made first and shared by every piece), and this holds it to
// that wherever pieces are closed by prisms, recursed or repaired.
TEST(Reconstruction, EveryShapeKeepsEveryContourPointAsAVertex) {
    struct Variant {
        double spacingMm, noiseMm;
        Interpolation interpolation;
        CapMode cap;
    };
    const Variant variants[] = {{2, 0, Interpolation::Smooth, CapMode::Flat},
                                {5, 0, Interpolation::Smooth, CapMode::Flat},
                                {5, 0, Interpolation::Linear, CapMode::Dome},
                                {3, 0.05, Interpolation::Smooth, CapMode::Flat}};
    for (const std::string& name : allShapeNames())
        for (const Variant& v : variants) {
            SCOPED_TRACE(name + " at " + std::to_string(v.spacingMm) + " mm, noise " +
                         std::to_string(v.noiseMm));
            SynthOptions synth;
            synth.spacingMm = v.spacingMm;
            synth.noiseMm = v.noiseMm;
            const Roi roi = sliceShape(*makeShape(name), synth).rois[0];
            ReconstructionOptions options;
            options.interpolation = v.interpolation;
            options.cap = v.cap;
            const Checked c = reconstruct(roi, options);
            EXPECT_TRUE(c.check.validSolid());
            expectContoursAreVertices(roi, c.result.surface);
        }
}

TEST(Reconstruction, OneContourToTwoRecursesAndStaysValid) {
    const Roi roi = stack({{circle({0, 0}, 8)}, {circle({-5, 0}, 4), circle({5, 0}, 4)}});
    const Checked c = reconstruct(roi);
    expectSolid(c, 0, 1);
    expectContoursAreVertices(roi, c.result.surface);
    EXPECT_GT(c.result.stats.recursions, 0u);
}

TEST(Reconstruction, TwoContoursToOneIsTheMirrorCase) {
    const Roi roi = stack({{circle({-5, 0}, 4), circle({5, 0}, 4)}, {circle({0, 0}, 8)}});
    const Checked c = reconstruct(roi);
    expectSolid(c, 0, 1);
    EXPECT_GT(c.result.stats.recursions, 0u);
}

TEST(Reconstruction, TwoToTwoCrossingBranches) {
    // Each lower circle overlaps both upper ones: one connected piece.
    const Roi roi = stack({{circle({-5, 0}, 4.5), circle({5, 0}, 4.5)},
                           {circle({0, -5}, 4.5), circle({0, 5}, 4.5)},
                           {circle({-5, 0}, 4.5), circle({5, 0}, 4.5)}});
    const Checked c = reconstruct(roi);
    EXPECT_TRUE(c.check.validSolid());
    EXPECT_EQ(c.check.components, 1u);
    expectContoursAreVertices(roi, c.result.surface);
}

TEST(Reconstruction, AtDepthZeroBranchesAreClosedByPrismsAndStillValid) {
    ReconstructionOptions options;
    options.maxDepth = 0;
    const Roi roi = stack({{circle({0, 0}, 8)}, {circle({-5, 0}, 4), circle({5, 0}, 4)}});
    const Checked c = reconstruct(roi, options);
    expectSolid(c, 0, 1);
    EXPECT_EQ(c.result.stats.recursions, 0u);
    EXPECT_GT(c.result.stats.limitClosings, 0u);
}

TEST(Reconstruction, ContourAppearingMidStackIsCappedBothWays) {
    std::vector<std::vector<Polygon>> slices(5, {circle({0, 0}, 6)});
    slices[2].push_back(circle({20, 0}, 3));
    const Checked c = reconstruct(stack(slices));
    expectSolid(c, 0, 2);
    EXPECT_EQ(c.result.stats.caps, 4u);  // the long stack's two ends, the blob's two
}

TEST(Reconstruction, TubeWithHolesIsGenusOne) {
    std::vector<std::vector<Polygon>> slices(4, {circle({0, 0}, 10), circle({0, 0}, 4)});
    const Checked c = reconstruct(stack(slices));
    expectSolid(c, 1, 1);
}

TEST(Reconstruction, CavityAndIslandInsideItGiveThreeSurfaces) {
    // A disc stack with a hole in the middle slices, and an island in the
    // hole on the middle slice: outer surface, cavity, and the island's solid.
    std::vector<std::vector<Polygon>> slices(5, {circle({0, 0}, 12)});
    for (int s = 1; s <= 3; ++s) slices[std::size_t(s)].push_back(circle({0, 0}, 7));
    slices[2].push_back(circle({0, 0}, 3));
    const Checked c = reconstruct(stack(slices));
    expectSolid(c, 0, 3);
}

// Is `p` inside the closed surface: field/Rasterization's exact ray parity
// for a one-voxel grid centred at p.
bool insideSolid(const TriangleSoup& surface, Vec3 p) {
    VolumeGeometry one;
    one.size = {1, 1, 1};
    one.originMm = {p.x, p.y, p.z};
    return !voxelsInsideSolid(surface, PlaneFrame{}, one).empty();
}

// A cavity whose last section lies on the end plane (a thick shell cut
// near its pole): the hole there is smaller than on the next plane in, so
// the cavity closes beyond the end, under a lid of its own inside the
// cap. Capped with the rest it would run through the cap as a tunnel from
// the cavity to the outside (one surface instead of two).
std::vector<std::vector<Polygon>> shellCutNearItsPole() {
    return {{circle({0, 0}, 10), circle({0, 0}, 3)},
            {circle({0, 0}, 12), circle({0, 0}, 8)},
            {circle({0, 0}, 12), circle({0, 0}, 8)},
            {circle({0, 0}, 10)}};
}

TEST(Reconstruction, CavityNarrowingTowardTheEndPlaneClosesInsideTheCap) {
    for (CapMode cap : {CapMode::Flat, CapMode::Dome})
        for (Interpolation interpolation : {Interpolation::Linear, Interpolation::Smooth}) {
            SCOPED_TRACE(std::string(capModeName(cap)) +
                         (interpolation == Interpolation::Linear ? " linear" : " smooth"));
            ReconstructionOptions options;
            options.cap = cap;
            options.interpolation = interpolation;
            const Roi roi = stack(shellCutNearItsPole());
            const Checked c = reconstruct(roi, options);
            expectSolid(c, 0, 2);
            expectContoursAreVertices(roi, c.result.surface);
            // Under the cavity, between its lid and the outer one (half the
            // 2 mm spacing below the end plane), the axis is solid; in the
            // cavity, just below the end plane, it is not.
            EXPECT_TRUE(insideSolid(c.result.surface, {0, 0, -0.9}));
            EXPECT_FALSE(insideSolid(c.result.surface, {0, 0, -0.05}));
            EXPECT_FALSE(insideSolid(c.result.surface, {0, 0, 1}));
        }
}

TEST(Reconstruction, CavityEndingBetweenPlanesNarrowsAsItsTrendSays) {
    // The cavity's last contour (r 4) is half the one above it (r 8), 2 mm
    // apart: it closes about 2 mm further down, so its cap (reaching the
    // middle of the gap, 1 mm down) narrows to about r 2 there instead of
    // keeping r 4 as a vertical wall would.
    for (Interpolation interpolation : {Interpolation::Linear, Interpolation::Smooth}) {
        SCOPED_TRACE(interpolation == Interpolation::Linear ? "linear" : "smooth");
        ReconstructionOptions options;
        options.interpolation = interpolation;
        const Roi roi = stack({{circle({0, 0}, 12)},
                               {circle({0, 0}, 12), circle({0, 0}, 4)},
                               {circle({0, 0}, 12), circle({0, 0}, 8)},
                               {circle({0, 0}, 12), circle({0, 0}, 8)},
                               {circle({0, 0}, 12)}});
        const Checked c = reconstruct(roi, options);
        expectSolid(c, 0, 2);
        EXPECT_FALSE(insideSolid(c.result.surface, {0, 0, 1.1}));
        EXPECT_TRUE(insideSolid(c.result.surface, {3.2, 0, 1.1}));
        EXPECT_FALSE(insideSolid(c.result.surface, {3.2, 0, 1.9}));
    }
}

TEST(Reconstruction, BoreWideningTowardTheEndPlaneStaysOpen) {
    // A bowl: the hole grows toward the top plane, so it stays open there.
    const Roi roi = stack({{circle({0, 0}, 10)},
                           {circle({0, 0}, 11), circle({0, 0}, 5)},
                           {circle({0, 0}, 12), circle({0, 0}, 9)}});
    const Checked c = reconstruct(roi);
    expectSolid(c, 0, 1);
}

TEST(Reconstruction, FlatCapsOnStraightSidesGiveThePlanningVolume) {
    // Identical squares: vertical sides, so each end extends exactly half a
    // spacing and the volume is area x slices x spacing.
    const Roi roi =
        stack({{squareContour(0, 0, 10)}, {squareContour(0, 0, 10)}, {squareContour(0, 0, 10)}});
    const Checked c = reconstruct(roi);
    expectSolid(c, 0, 1);
    EXPECT_NEAR(c.check.volumeMm3, 100 * 3 * 2, 1e-9);
    ReconstructionOptions options;
    options.capOffsetMm = 0.25;
    EXPECT_NEAR(reconstruct(roi, options).check.volumeMm3, 100 * (2 * 2 + 2 * 0.25), 1e-9);
}

TEST(Reconstruction, CapModesCloseANarrowingEnd) {
    // A lens-like stack whose sections' areas lie on a parabola: the end
    // slabs narrow from radius 10 to 6 over 2 mm. The flat lid, 1 mm out,
    // is inset by the end parabola's slope (4 mm per mm, twice the slabs'
    // secant: recon/HermiteTangents), the dome rises to the offset over the
    // whole end region, and with no cap the ends stay open.
    const Roi roi = stack({{circle({0, 0}, 6)}, {circle({0, 0}, 10)}, {circle({0, 0}, 6)}});
    ReconstructionOptions options;
    const Checked flat = reconstruct(roi, options);
    expectSolid(flat, 0, 1);
    options.cap = CapMode::Dome;
    const Checked dome = reconstruct(roi, options);
    expectSolid(dome, 0, 1);
    options.cap = CapMode::None;
    const Checked none = reconstruct(roi, options);
    EXPECT_EQ(none.check.boundaryEdges, 2u * 48u);
    EXPECT_EQ(none.check.nonManifoldEdges + none.check.misorientedEdges, 0u);
    EXPECT_LT(flat.check.volumeMm3, dome.check.volumeMm3);
    EXPECT_LT(std::abs(none.check.volumeMm3), flat.check.volumeMm3);
}

TEST(Reconstruction, DomesOverSpikyContoursDoNotMeetTheirMirror) {
    // A single slice is capped up and down: its two domes share the contour
    // and must not share anything else (no flat ears or chords between
    // narrow lobes).
    Polygon star;
    for (int k = 0; k < 40; ++k) {
        const double a = 2 * M_PI * k / 40, r = k % 2 ? 3.0 : 9.0;
        star.push_back({r * std::cos(a), r * std::sin(a)});
    }
    ReconstructionOptions options;
    options.cap = CapMode::Dome;
    const Checked c = reconstruct(stack({{star}}), options);
    expectSolid(c, 0, 1);
}

TEST(Reconstruction, SingleSliceBecomesAFlatSlab) {
    const Checked c = reconstruct(stack({{squareContour(0, 0, 10)}}));
    expectSolid(c, 0, 1);
    EXPECT_NEAR(c.check.volumeMm3, 100 * 1.0, 1e-9);  // 1 mm thick without a spacing
}

TEST(Reconstruction, ContourSimplificationKeepsItValidWithFewerPoints) {
    SynthOptions synth;
    synth.pointsPerContour = 256;
    const ContourSet set = sliceShape(*makeShape("torus"), synth);
    ReconstructionOptions options;
    options.contourErrorMm = 0.1;
    const Checked coarse = reconstruct(set.rois[0], options);
    const Checked full = reconstruct(set.rois[0]);
    expectSolid(coarse, 1, 1);
    EXPECT_LT(coarse.check.triangles * 2, full.check.triangles);
}

TEST(Reconstruction, NoisyContoursStayValidSolids) {
    // Vertex noise comparable to the edge length makes contours zigzag; a
    // strip that would fold through itself is solved again with intermediate
    // contours, holes included (torus). (Other shapes' small end contours
    // cannot take this much noise without crossing themselves.)
    std::size_t rejected = 0;
    for (const std::string name : {"torus", "capsule"})
        for (unsigned seed : {1u, 2u, 3u}) {
            SCOPED_TRACE(name + " seed " + std::to_string(seed));
            SynthOptions options;
            options.spacingMm = 7;
            options.pointsPerContour = 90;
            options.noiseMm = 0.3;
            options.seed = seed;
            const Checked c = reconstruct(sliceShape(*makeShape(name), options).rois[0]);
            EXPECT_TRUE(c.check.validSolid());
            EXPECT_EQ(c.check.genus, name == "torus" ? 1 : 0);
            rejected += c.result.stats.rejectedStrips;
        }
    EXPECT_GT(rejected, 0u) << "the fallback was exercised";
}

TEST(Reconstruction, ASmallContourBelowALargeOneKeepsTheSlabsVolume) {
    // The lowest two planes of an atlas area (AAL label 87 cut every 3 mm,
    // made by truth_set.py --gap 3): two small contours below a large one
    // they only partly lie under. The summed fields' zero set pinched to a
    // waist of 8 mm² between sections of 28 and 224 mm², and the solid held
    // 0.66 of its contour volume (the slab a third of what its sections
    // imply). With the intermediate contours raised to the mean of the
    // sections' areas it holds 0.86–0.87, in both modes.
    const ContourSet set =
        readSlicesFile(std::string(DFRECON_TEST_DATA) + "/recon/atlas-area-end.slices").contours;
    const Roi& roi = set.rois[0];
    for (const Interpolation mode : {Interpolation::Linear, Interpolation::Smooth}) {
        ReconstructionOptions options;
        options.interpolation = mode;
        const Checked c = reconstruct(roi, options);
        // A valid closed solid; its genus between the planes is the
        // interpolation's (the contours do not decide it).
        EXPECT_TRUE(c.check.validSolid());
        expectContoursAreVertices(roi, c.result.surface);
        const double ratio = c.check.volumeMm3 / contourVolumeMm3(roi);
        EXPECT_GT(ratio, 0.8);
        EXPECT_LT(ratio, 1.0);
    }
}

TEST(Reconstruction, APlaneThatBarelyCutsTheStructureKeepsTheSlabsVolume) {
    // The lowest three planes of AAL label 25 cut every 2 mm (truth_set.py
    // --axis z --gap 2): a speck of 6.5 mm² under a section of 522 mm² (the
    // area's floor lies between the planes). The summed fields stay high
    // far from the speck, so the intermediate contour could not rise to its
    // target within one slab height of level: the slab held 198 of the
    // 528 mm³ its sections imply. Joined through an intermediate contour
    // whose level may rise further (still within the two regions), it holds
    // 0.97 of that, in both modes.
    const ContourSet set =
        readSlicesFile(std::string(DFRECON_TEST_DATA) + "/recon/atlas-area-floor.slices").contours;
    const Roi& roi = set.rois[0];
    const double z0 = roi.slices[0].zMm, z1 = roi.slices[1].zMm;
    const double implied =
        0.5 * (z1 - z0) * (netArea(roi.slices[0].contours) + netArea(roi.slices[1].contours));
    for (const Interpolation mode : {Interpolation::Linear, Interpolation::Smooth}) {
        ReconstructionOptions options;
        options.interpolation = mode;
        const Checked c = reconstruct(roi, options);
        EXPECT_TRUE(c.check.validSolid());
        expectContoursAreVertices(roi, c.result.surface);
        const double slab =
            volumeBelowPlane(c.result.surface, z1) - volumeBelowPlane(c.result.surface, z0);
        EXPECT_GT(slab / implied, 0.85) << int(mode);
        EXPECT_LT(slab / implied, 1.15) << int(mode);
    }
}

TEST(Reconstruction, SlabsWhosePiecesMeetAreClosedAsOnePrismPiece) {
    // Stacks of scripts/random_blobs.py (seeds 7 and 329) with a slab whose
    // pieces meet, and three that had one until the intermediate contours
    // were raised to the sections' mean area (235, 338) or to its cubic
    // trend (219): all valid solids.
    for (const char* name :
         {"random-blobs-7.slices", "random-blobs-329.slices", "random-blobs-219.slices",
          "random-blobs-235.slices", "random-blobs-338.slices"}) {
        SCOPED_TRACE(name);
        const ContourSet set =
            readSlicesFile(std::string(DFRECON_TEST_DATA) + "/recon/" + name).contours;
        const Checked c = reconstruct(set.rois[0]);
        EXPECT_TRUE(c.check.validSolid());
        if (std::string(name).find("-7.") != std::string::npos ||
            std::string(name).find("329") != std::string::npos)
            EXPECT_GT(c.result.stats.fallbackSlabs, 0u) << "the fallback was exercised";
        expectContoursAreVertices(set.rois[0], c.result.surface);
        EXPECT_EQ(c.check.vertices, c.result.surface.points.size()) << "no unused points";
    }
}

// Where bent bands pass through each other, the broken triangles' corners
// first go halfway back to the straight surface: on this stack every
// crossing parts that way (each had put its vertex and a ring of
// neighbours straight before), and the surface stays a valid solid through
// every contour point.
TEST(Reconstruction, BentBandsThatMeetGiveBackHalfTheirBendFirst) {
    const ContourSet set =
        readSlicesFile(std::string(DFRECON_TEST_DATA) + "/recon/random-blobs-329.slices").contours;
    const Checked c = reconstruct(set.rois[0]);
    EXPECT_TRUE(c.check.validSolid());
    EXPECT_GT(c.result.stats.smoothHalfUnbentVertices, 0u) << "bands met and were eased apart";
    EXPECT_EQ(c.result.stats.smoothUnbentVertices, 0u) << "none had to go back straight";
    EXPECT_EQ(c.result.stats.smoothRevertedPieces, 0u);
    expectContoursAreVertices(set.rois[0], c.result.surface);
}

// Heschl's gyrus (AAL label 80 cut every 2 mm, truth_set.py --gap 2), one
// of the small areas issue 66 names: thin and oblique, so a point on one
// face lies across the next plane's medial axis. The tangents read the far
// face there and bent the near one out; the folds that made, and their
// repairs (1141 of its 1581 bent vertices went back straight, two slabs
// kept linear), left it 4.2 % below its contour volume. With the far face's
// secant weighed down it is within 1 %, with no piece kept linear.
TEST(Reconstruction, AThinObliqueGyrusKeepsItsContourVolume) {
    const ContourSet set =
        readSlicesFile(std::string(DFRECON_TEST_DATA) + "/recon/heschl-gyrus.slices").contours;
    const Roi& roi = set.rois[0];
    const Checked c = reconstruct(roi);
    EXPECT_TRUE(c.check.validSolid());
    expectContoursAreVertices(roi, c.result.surface);
    EXPECT_EQ(c.result.stats.smoothRevertedPieces, 0u);
    EXPECT_NEAR(c.check.volumeMm3 / contourVolumeMm3(roi), 1.0, 0.01);
}

TEST(Reconstruction, ASlabWhoseCapsMeetIsGivenUpBeforeItsBranchesAreBuilt) {
    // Two contours of neighbouring planes touch at a corner in projection, so
    // the lids of both (each ends in the slab) meet in its middle plane. The
    // caps are built first; their meeting already dooms the slab, so the
    // branch beside them gets no intermediate layer, and the slab is one
    // prism piece, as it was when everything was built and then checked.
    const ContourSet set =
        readSlicesFile(std::string(DFRECON_TEST_DATA) + "/recon/caps-touching-at-a-corner.slices")
            .contours;
    const Checked c = reconstruct(set.rois[0]);
    EXPECT_TRUE(c.check.validSolid());
    EXPECT_EQ(c.check.components, 3u);
    EXPECT_EQ(c.result.stats.fallbackSlabs, 1u);
    EXPECT_EQ(c.result.stats.recursions, 0u) << "the branch was built, then thrown away";
    expectContoursAreVertices(set.rois[0], c.result.surface);

    // Without the touching pair the same branch is built and kept.
    ContourSet apart = set;
    for (Slice& slice : apart.rois[0].slices)
        slice.contours.erase(std::remove_if(slice.contours.begin(), slice.contours.end(),
                                            [](const Polygon& p) { return p[0].x < 0; }),
                             slice.contours.end());
    const Checked branch = reconstruct(apart.rois[0]);
    EXPECT_TRUE(branch.check.validSolid());
    EXPECT_EQ(branch.result.stats.fallbackSlabs, 0u);
    EXPECT_GT(branch.result.stats.recursions, 0u);
}

}  // namespace
}  // namespace dfrecon
