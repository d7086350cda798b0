// Error-bounded simplification, checked by the independent verifier
// (simplify/SimplificationVerifier: dense samples, exact distances over a BVH):
// both directions against the unsimplified mesh and against the contours,
// on every synth shape at three bounds.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <random>

#include "geometry/MeshCheck.hpp"
#include "io/contours/SlicesFile.hpp"
#include "recon/Reconstruction.hpp"
#include "shapes/AnalyticShapes.hpp"
#include "simplify/CollapseBound.hpp"
#include "simplify/DeviationBound.hpp"
#include "simplify/InitialPriorities.hpp"
#include "simplify/Simplification.hpp"
#include "simplify/SimplificationVerifier.hpp"
#include "tests/CpuRuntime.hpp"

namespace dfrecon {
namespace {

struct Case {
    Roi roi;
    TriangleSoup surface;
};

Case reconstructed(const std::string& shape, double spacingMm,
                   Interpolation interpolation = Interpolation::Smooth) {
    SynthOptions options;
    options.spacingMm = spacingMm;
    Case c;
    c.roi = sliceShape(*makeShape(shape), options).rois[0];
    ReconstructionOptions recon;
    recon.interpolation = interpolation;
    c.surface = reconstructSurface(cpuRuntime(), c.roi, recon).surface;
    return c;
}

// Runs the simplifier and the verifier; returns the simplified surface.
TriangleSoup simplifyAndVerify(const Case& c, double maxErrorMm) {
    SimplifyOptions options;
    options.maxErrorMm = maxErrorMm;
    const Simplified s = simplifySurface(&cpuRuntime(), c.surface, options);
    const MeshCheckReport before = checkMesh(c.surface), after = checkMesh(s.surface);
    EXPECT_TRUE(after.validSolid())
        << "watertight " << after.watertight() << ", intersecting " << after.intersectingPairs;
    EXPECT_EQ(after.genus, before.genus);
    EXPECT_EQ(after.components, before.components);
    EXPECT_LT(s.stats.triangles, s.stats.trianglesBefore);
    EXPECT_LE(s.stats.surfaceToInputBoundMm, maxErrorMm);
    EXPECT_LE(s.stats.inputToSurfaceBoundMm, maxErrorMm);
    const SimplificationDistance d =
        verifySimplification(c.surface, s.surface, &c.roi, maxErrorMm / 8, 20000);
    EXPECT_LE(d.surfaces.maxMm(), maxErrorMm);
    EXPECT_LE(d.contours.maxMm, maxErrorMm);
    EXPECT_GT(d.contours.samples, 0u);
    return s.surface;
}

// One test per shape, so ctest runs them in parallel. Sanitizer builds run
// ten times slower; they check the middle bound on the coarser stacks.
class EveryShape : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryShape, StaysWithinTheBoundBothWays) {
#ifdef DFRECON_SANITIZE_BUILD
    const std::vector<double> bounds{0.5};
    const double spacingMm = 5.0;
#else
    const std::vector<double> bounds{0.25, 0.5, 1.0};
    const double spacingMm = 2.0;
#endif
    const Case c = reconstructed(GetParam(), spacingMm);
    for (double bound : bounds) {
        SCOPED_TRACE(std::to_string(bound) + " mm");
        simplifyAndVerify(c, bound);
    }
}

INSTANTIATE_TEST_SUITE_P(Simplification, EveryShape, ::testing::ValuesIn(shapeNames()),
                         [](const ::testing::TestParamInfo<std::string>& shape) {
                             std::string name = shape.param;
                             for (char& ch : name)
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             return name;
                         });

// A harsh random stack (scripts/random_blobs.py 1 --harsh) on which a
// collapse queued earlier went stale before being taken and left a contour
// 0.2537 mm away at 0.25 (fixed by re-checking every collapse when taken).
TEST(Simplification, RandomHarshStackStaysWithinTheBound) {
    Case c;
    c.roi = readSlicesFile(std::string(DFRECON_TEST_DATA) + "/simplify/random-blobs-1-harsh.slices")
                .contours.rois[0];
    c.surface = reconstructSurface(cpuRuntime(), c.roi).surface;
    simplifyAndVerify(c, 0.25);
}

// A shape reconstructed at 2 mm spacing, its hierarchy and a seeded random
// source: the deviation tests draw triangles near its surface.
struct NearSurface {
    // Straight strips: the trials' offsets (up to 0.3 mm off a fan's
    // triangles) were chosen so that both outcomes occur on their fans.
    NearSurface(const std::string& shape, unsigned seed)
        : c(reconstructed(shape, 2.0, Interpolation::Linear)), original(c.surface), rng(seed) {}
    double unit() { return std::uniform_real_distribution<double>(-1, 1)(rng); }
    Case c;
    DeviationSurface original;
    std::mt19937 rng;
};

// The deviation bound against brute force: when within the limit it is
// never below the largest distance found by dense sampling, and it says
// "over" whenever sampling finds a point over.
TEST(DeviationBound, BoundsDenseSamplesFromAbove) {
    NearSurface sphere("sphere", 5);
    const DeviationSurface& original = sphere.original;
    const DeviationLimits limits{0.5};
    int over = 0, under = 0;
    for (int trial = 0; trial < 300; ++trial) {
        // A triangle with its corners up to 3 mm from a point of the sphere
        // (radius 20 mm), at radius 20 ± 0.6 mm: some within the limit,
        // some not.
        const Vec3 dir{sphere.unit(), sphere.unit(), sphere.unit()};
        const Vec3 centre = (20.0 / length(dir)) * dir;
        Vec3 p[3];
        for (Vec3& q : p) {
            const Vec3 r = centre + Vec3{3 * sphere.unit(), 3 * sphere.unit(), 3 * sphere.unit()};
            q = ((20.0 + 0.6 * sphere.unit()) / length(r)) * r;
        }
        const double bound = deviationBound(original, p[0], p[1], p[2], limits);
        double sampled = 0;
        for (int i = 0; i <= 40; ++i)
            for (int j = 0; i + j <= 40; ++j) {
                const double u = i / 40.0, v = j / 40.0;
                const Vec3 q = p[0] + u * (p[1] - p[0]) + v * (p[2] - p[0]);
                sampled = std::max(sampled, original.bvh.nearest(q).distance);
            }
        // Within the limit the value is an upper bound; over it, only "over"
        // is promised.
        if (bound <= limits.limitMm) {
            EXPECT_GE(bound + 1e-12, sampled);
        }
        if (sampled > limits.limitMm) {
            EXPECT_GT(bound, limits.limitMm);
        }
        (bound <= limits.limitMm ? under : over)++;
    }
    EXPECT_GT(under, 20);  // both outcomes exercised
    EXPECT_GT(over, 20);
}

// The fan rule alone against brute force: triangles with corners on the
// fan of a vertex of the torus, lifted off it by up to 0.3 mm. Where the
// rule settles one, no dense sample of it is farther from the fan than the
// value; pieces reaching past the fan are refused.
TEST(DeviationBound, FanRuleBoundsDenseSamplesFromAbove) {
    NearSurface torus("torus", 17);
    const DeviationSurface& original = torus.original;
    const TriangleSoup& soup = torus.c.surface;
    const double limit = 0.5;
    int settled = 0, refused = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const std::uint32_t v = std::uint32_t(torus.rng() % soup.points.size());
        const std::uint32_t first = original.fans.first()[v];
        const std::uint32_t m = std::uint32_t(original.fans.neighbours(v));
        ASSERT_GE(m, 3u) << "every vertex of the torus has a fan";
        std::vector<std::array<Vec3, 3>> fan;
        for (std::uint32_t k = 0; k < m; ++k)
            fan.push_back({soup.points[v], soup.points[original.fans.ring()[first + k]],
                           soup.points[original.fans.ring()[first + (k + 1) % m]]});
        Vec3 p[3];
        for (Vec3& q : p) {
            const auto& t = fan[std::size_t(torus.rng() % m)];
            const double s = 0.5 * (torus.unit() + 1), r = 0.5 * (torus.unit() + 1) * (1 - s);
            const Vec3 n = cross(t[1] - t[0], t[2] - t[0]);
            q = t[0] + s * (t[1] - t[0]) + r * (t[2] - t[0]) + (0.3 * torus.unit() / length(n)) * n;
        }
        const double bound = fanDistance(original, p[0], p[1], p[2], v, limit);
        double sampled = 0;
        for (int i = 0; i <= 30; ++i)
            for (int j = 0; i + j <= 30; ++j) {
                const Vec3 q = p[0] + (i / 30.0) * (p[1] - p[0]) + (j / 30.0) * (p[2] - p[0]);
                double nearest = INFINITY;
                for (const auto& t : fan)
                    nearest = std::min(nearest, pointTriangleDistance(q, t[0], t[1], t[2]));
                sampled = std::max(sampled, nearest);
            }
        if (bound <= limit) {
            EXPECT_GE(bound + 1e-12, sampled) << "trial " << trial;
            ++settled;
        } else {
            ++refused;
        }
    }
    EXPECT_GT(settled, 50);  // both outcomes exercised
    EXPECT_GT(refused, 20);
}

// The lazy queue's lower bounds: an estimate from a few pieces never
// exceeds the bound, says "over" only when the bound does, and is the bound
// when it says it is complete.
TEST(DeviationBound, EstimatesFromFewPiecesAreLowerBounds) {
    NearSurface torus("torus", 7);
    const DeviationLimits limits{0.25};
    int incomplete = 0, complete = 0;
    for (int trial = 0; trial < 200; ++trial) {
        // Big triangles through vertices of the surface: many pieces each.
        const auto& points = torus.c.surface.points;
        const Vec3 a = points[std::size_t(torus.rng() % points.size())];
        const Vec3 b = a + Vec3{4 * torus.unit(), 4 * torus.unit(), 2 * torus.unit()};
        const Vec3 d = a + Vec3{4 * torus.unit(), 4 * torus.unit(), 2 * torus.unit()};
        const DeviationSurface& original = torus.original;
        const double bound = deviationBound(original, a, b, d, limits);
        for (std::size_t pieces : {std::size_t(1), std::size_t(8), std::size_t(64)}) {
            const DeviationEstimate e = deviationBoundWithin(original, a, b, d, limits, {pieces});
            if (e.complete) {
                EXPECT_EQ(e.value, bound);
                ++complete;
            } else {
                EXPECT_LE(e.value, bound);
                EXPECT_LE(e.value, limits.limitMm);
                ++incomplete;
            }
        }
    }
    EXPECT_GT(complete, 20);  // both outcomes exercised
    EXPECT_GT(incomplete, 20);
}

// Asked only whether the bound is at most `enough`, an estimate stops at the
// first piece that shows more: still a lower bound, above `enough` unless
// complete, and never weaker than the same budget's estimate up to that
// piece. Through the cache (any order of questions) and over a collapse's
// triangles, the same holds, and with nothing above `enough` the answer is
// surfaceDeviation's.
TEST(DeviationBound, EstimatesStopOnceAboveWhatTheCallerAsks) {
    NearSurface torus("torus", 11);
    const DeviationLimits limits{0.25};
    const DeviationSurface& original = torus.original;
    const auto& points = torus.c.surface.points;
    int stoppedEarly = 0, answeredInFull = 0;
    DeviationCache cache;
    for (int trial = 0; trial < 150; ++trial) {
        // A fan of triangles between vertices of the surface up to 4 mm
        // apart: chords of the torus, some within the limit, some not.
        const Vec3 a = points[std::size_t(torus.rng() % points.size())];
        std::vector<Vec3> near;
        for (const Vec3& q : points)
            if (length(q - a) > 0.5 && length(q - a) < 4) near.push_back(q);
        ASSERT_GE(near.size(), 2u);
        std::vector<NewTriangle> created(3);
        for (NewTriangle& t : created) {
            t.p[0] = a;
            t.p[1] = near[std::size_t(torus.rng() % near.size())];
            t.p[2] = near[std::size_t(torus.rng() % near.size())];
            t.ids = {std::uint32_t(3 * trial), std::uint32_t(3 * trial + 1 + (&t - &created[0])),
                     std::uint32_t(3 * trial + 9000)};
        }
        const NewTriangle& t = created[0];
        const double bound = deviationBound(original, t.p[0], t.p[1], t.p[2], limits);
        const double enough = 0.125 * (torus.unit() + 1) + 0.02;  // over [0.02, 0.27)
        for (std::size_t pieces : {std::size_t(8), std::size_t(64), SIZE_MAX}) {
            const DeviationEstimate e =
                deviationBoundWithin(original, t.p[0], t.p[1], t.p[2], limits, {pieces, enough});
            if (e.complete) {
                EXPECT_EQ(e.value, bound);
                continue;
            }
            EXPECT_LE(e.value, bound);
            if (e.piecesTaken < pieces) {
                EXPECT_GT(e.value, enough);
                ++stoppedEarly;
                // As strong as the same pieces without the question.
                const DeviationEstimate same =
                    deviationBoundWithin(original, t.p[0], t.p[1], t.p[2], limits, {e.piecesTaken});
                EXPECT_EQ(same.value, e.value);
            }
        }
        // The cache and the collapse-level lower bound: questions in a random
        // order, each answer a lower bound, above `enough` or exact.
        const float full = surfaceDeviation(created, original, limits);
        for (int ask = 0; ask < 3; ++ask) {
            const double asked = 0.15 * (torus.unit() + 1);
            const std::size_t budgets[] = {1, 8, 64, SIZE_MAX};
            const std::size_t pieces = budgets[torus.rng() % 4];
            const float lower =
                surfaceDeviationLowerBound(created, original, limits, cache, pieces, asked);
            if (full < 0) {
                EXPECT_TRUE(lower < 0 || lower <= limits.limitMm);
                continue;
            }
            EXPECT_GE(lower, 0.0f);
            EXPECT_LE(lower, std::nextafter(full, INFINITY));
            if (pieces == SIZE_MAX && lower <= asked) {
                EXPECT_NEAR(lower, full, 1e-6 * (1 + full));
                ++answeredInFull;
            }
        }
        EXPECT_EQ(surfaceDeviationLowerBound(created, original, limits, cache, SIZE_MAX) < 0,
                  full < 0);
    }
    EXPECT_GT(stoppedEarly, 20);  // both outcomes exercised
    EXPECT_GT(answeredInFull, 5);
}

// The cache grows as triangles come (from 1 024 slots): every value it
// returns afterwards is still the one computed for that triangle.
TEST(DeviationCache, KeepsEveryValueAsItGrows) {
    NearSurface torus("torus", 13);
    const DeviationLimits limits{0.25};
    const auto& soup = torus.c.surface;
    DeviationCache cache;
    std::vector<double> first;
    // Each original triangle, and one with a corner moved off the surface
    // (ids shifted past the originals'), so that values differ.
    auto triangle = [&](std::size_t t, bool moved) {
        NewTriangle n;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t id = soup.triangles[t][std::size_t(k)];
            n.ids[std::size_t(k)] = id + (moved ? std::uint32_t(soup.points.size()) : 0);
            n.p[k] = soup.points[id];
        }
        if (moved) n.p[0] = n.p[0] + Vec3{0.05 * double(t % 7), 0, 0};
        return n;
    };
    for (std::size_t t = 0; t < soup.triangles.size(); ++t)
        for (bool moved : {false, true})
            first.push_back(cache.bound(triangle(t, moved), torus.original, limits));
    ASSERT_GT(first.size(), 4000u);
    std::size_t i = 0;
    for (std::size_t t = 0; t < soup.triangles.size(); ++t)
        for (bool moved : {false, true}) {
            const NewTriangle n = triangle(t, moved);
            EXPECT_EQ(cache.estimate(n, torus.original, limits, 1), first[i]);
            EXPECT_NEAR(first[i], deviationBound(torus.original, n.p[0], n.p[1], n.p[2], limits),
                        1e-6);
            ++i;
        }
}

TEST(DeviationBound, FlatTriangleAboveAPlaneIsBoundedByItsHeight) {
    // Over one big triangle the corner rule settles at once: exactly the
    // height. Over two, pieces across the diagonal settle by distance plus
    // radius: still a bound, at most the limit.
    TriangleSoup plane;
    plane.points = {{-10, -10, 0}, {30, -10, 0}, {-10, 30, 0}, {10, 10, 0}};
    plane.triangles = {{0, 1, 2}};
    const Vec3 a{-2, -1, 0.2}, b{3, -1, 0.2}, c{0, 4, 0.2};
    EXPECT_NEAR(deviationBound(DeviationSurface(plane), a, b, c, {0.5}), 0.2, 1e-12);
    plane.triangles = {{0, 1, 3}, {0, 3, 2}};
    const DeviationSurface split(plane);
    const double bound = deviationBound(split, a, b, c, {0.5});
    EXPECT_GE(bound, 0.2 - 1e-12);
    EXPECT_LE(bound, 0.5);
    EXPECT_GT(deviationBound(split, a, b, c, {0.1}), 0.1);
}

// The OpenCL batch against its C++ reference on every halfedge: the same
// legality and, where legal, the same value (in double on devices with
// fp64 and without contraction the two agree to rounding; in float within
// the slack the host adds).
TEST(InitialPriorities, KernelMatchesReference) {
    for (const char* shape : {"sphere", "torus", "y"}) {
        const Case c = reconstructed(shape, 5.0);
        const TriMesh mesh = toTriMesh(c.surface);
        const DeviationSurface original(c.surface);
        for (double bound : {0.25, 1.0}) {
            const std::vector<float> device =
                initialPriorities(cpuRuntime(), mesh, original, bound);
            const std::vector<float> reference = initialPrioritiesReference(mesh, original, bound);
            ASSERT_EQ(device.size(), reference.size());
            std::size_t legal = 0, mismatched = 0;
            for (std::size_t h = 0; h < device.size(); ++h) {
                if ((device[h] < 0) != (reference[h] < 0)) {
                    ++mismatched;  // only a value within rounding of the bound may flip
                    EXPECT_NEAR(std::max(device[h], reference[h]), bound, 1e-4) << "halfedge " << h;
                    continue;
                }
                if (reference[h] < 0) continue;
                ++legal;
                EXPECT_NEAR(device[h], reference[h], 1e-4) << "halfedge " << h;
            }
            EXPECT_GT(legal, device.size() / 10) << shape;
            EXPECT_LE(mismatched, device.size() / 1000) << shape;
        }
    }
}

TEST(InitialPriorities, UnwantedHalfedgesAreSkippedTheOthersUnchanged) {
    const Case c = reconstructed("torus", 5.0);
    const TriMesh mesh = toTriMesh(c.surface);
    const DeviationSurface original(c.surface);
    std::mt19937 random(4);
    std::vector<bool> wanted(mesh.n_halfedges());
    for (std::size_t h = 0; h < wanted.size(); ++h) wanted[h] = random() % 3 != 0;
    const std::vector<float> all = initialPriorities(cpuRuntime(), mesh, original, 0.5);
    const std::vector<float> some = initialPriorities(cpuRuntime(), mesh, original, 0.5, &wanted);
    const std::vector<float> allReference = initialPrioritiesReference(mesh, original, 0.5);
    const std::vector<float> someReference =
        initialPrioritiesReference(mesh, original, 0.5, &wanted);
    ASSERT_EQ(some.size(), all.size());
    ASSERT_EQ(someReference.size(), all.size());
    std::size_t legal = 0;
    for (std::size_t h = 0; h < all.size(); ++h) {
        EXPECT_EQ(some[h], wanted[h] ? all[h] : -1.0f) << "halfedge " << h;
        EXPECT_EQ(someReference[h], wanted[h] ? allReference[h] : -1.0f) << "halfedge " << h;
        legal += wanted[h] && all[h] >= 0;
    }
    EXPECT_GT(legal, all.size() / 10);
}

TEST(Simplification, RefusesBadOptionsAndNonManifoldInput) {
    const Case c = reconstructed("sphere", 5.0);
    SimplifyOptions options;
    options.maxErrorMm = 0;
    EXPECT_THROW(simplifySurface(&cpuRuntime(), c.surface, options), std::invalid_argument);
    TriangleSoup fin = c.surface;  // a third face on one edge
    const auto t = fin.triangles[0];
    fin.points.push_back({0, 0, 100});
    fin.triangles.push_back({t[0], t[1], std::uint32_t(fin.points.size() - 1)});
    options.maxErrorMm = 0.5;
    EXPECT_THROW(simplifySurface(&cpuRuntime(), fin, options), std::invalid_argument);
}

TEST(Simplification, CpuAndDeviceInitialBoundsGiveValidResults) {
    const Case c = reconstructed("torus", 5.0);
    SimplifyOptions options;
    options.maxErrorMm = 0.5;
    options.initialBatchOnDevice = false;
    const Simplified cpu = simplifySurface(nullptr, c.surface, options);
    EXPECT_EQ(cpu.stats.batchEvaluations + cpu.stats.cpuEvaluations > 0, true);
    EXPECT_TRUE(checkMesh(cpu.surface).validSolid());
    EXPECT_LE(twoSidedDistance(c.surface, cpu.surface, 20000).maxMm(), 0.5);
}

}  // namespace
}  // namespace dfrecon
