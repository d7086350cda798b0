// Closest primitives of the other objects: the OpenCL kernel and its C++
// reference against brute force over every triangle (distances within the
// kernel's stated tolerance, nearest object exact except at ties), signs
// against analytic inside tests, on random soups, analytic solids and real
// meshes from CGAL's data.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "field/ClosestPrimitives.hpp"
#include "io/mesh/MeshIO.hpp"
#include "sdm/SurfaceDistanceMaps.hpp"
#include "shapes/MeshShapes.hpp"

using namespace dfrecon;

namespace {

ocl::Runtime& runtime() {
    static ocl::Runtime r;
    return r;
}

TriangleSoup randomSoup(std::mt19937& random, Vec3 centre, int triangles) {
    std::uniform_real_distribution<double> offset(-10, 10);
    TriangleSoup soup;
    for (int t = 0; t < triangles; ++t) {
        const Vec3 base = centre + Vec3{offset(random), offset(random), offset(random)};
        for (int k = 0; k < 3; ++k)
            soup.points.push_back(base +
                                  0.3 * Vec3{offset(random), offset(random), offset(random)});
        const std::uint32_t first = std::uint32_t(3 * t);
        soup.triangles.push_back({first, first + 1, first + 2});
    }
    return soup;
}

std::vector<SurfaceSample> allSamples(const SurfaceScene& scene, int atlasSize) {
    std::vector<SurfaceSample> samples;
    for (std::size_t o = 0; o < scene.objectCount(); ++o) {
        const ObjectSamples s = sampleObject(scene, o, {atlasSize});
        samples.insert(samples.end(), s.samples.begin(), s.samples.end());
    }
    return samples;
}

// Distances agree within `tolerance`; the object agrees unless the brute
// force found a tie (another object within the tolerance).
void expectSameAnswers(const SurfaceScene& scene, const std::vector<SurfaceSample>& samples,
                       const std::vector<ClosestPrimitive>& got,
                       const std::vector<ClosestPrimitive>& want, double tolerance,
                       const DistanceQuery& query = {}) {
    ASSERT_EQ(got.size(), want.size());
    std::size_t objectMismatches = 0;
    for (std::size_t k = 0; k < got.size(); ++k) {
        ASSERT_EQ(got[k].object < 0, want[k].object < 0) << "sample " << k;
        if (want[k].object < 0) continue;
        ASSERT_NEAR(got[k].distanceMm, want[k].distanceMm, tolerance) << "sample " << k;
        EXPECT_NEAR(length(got[k].point - want[k].point), 0, 1e3 * tolerance + 1e-9);
        if (got[k].object != want[k].object) {
            // Only a tie may choose differently: the other object is as near.
            DistanceQuery only = query;
            only.target = got[k].object;
            const auto alt = closestPrimitivesBruteForce(scene, {samples[k]}, only);
            EXPECT_NEAR(std::abs(alt[0].distanceMm), std::abs(want[k].distanceMm), tolerance);
            ++objectMismatches;
        }
    }
    EXPECT_LE(objectMismatches, got.size() / 1000 + 1);
}

}  // namespace

TEST(ClosestPrimitives, RandomSoupsAgreeWithBruteForce) {
    std::mt19937 random(11);
    SurfaceScene scene({randomSoup(random, {0, 0, 0}, 300), randomSoup(random, {8, 0, 0}, 300),
                        randomSoup(random, {0, 9, 3}, 200)});
    for (std::size_t o = 0; o < 3; ++o) EXPECT_FALSE(scene.closed(o));
    const std::vector<SurfaceSample> samples = allSamples(scene, 48);
    ASSERT_GT(samples.size(), 3000u);
    const auto brute = closestPrimitivesBruteForce(scene, samples);
    const auto reference = closestPrimitivesReference(scene, samples);
    ClosestPrimitiveKernel kernel(runtime(), scene);
    const auto device = kernel.run(samples);
    expectSameAnswers(scene, samples, reference, brute, 1e-12);
    expectSameAnswers(scene, samples, device, brute, std::max(kernel.toleranceMm(), 1e-12));
    // The lists made a few sources at a time: the same answers.
    ClosestPrimitiveKernel chunked(runtime(), scene, 7);
    const auto inChunks = chunked.run(samples);
    for (std::size_t k = 0; k < samples.size(); ++k) {
        EXPECT_EQ(inChunks[k].object, device[k].object) << "sample " << k;
        EXPECT_EQ(inChunks[k].triangle, device[k].triangle) << "sample " << k;
        EXPECT_EQ(inChunks[k].distanceMm, device[k].distanceMm) << "sample " << k;
    }
    for (std::size_t k = 0; k < samples.size(); ++k) {
        EXPECT_NE(std::size_t(device[k].object), samples[k].object);
        EXPECT_GE(device[k].distanceMm, 0) << "open soups are unsigned";
    }
}

TEST(ClosestPrimitives, SignsAndDistancesOfOverlappingSpheres) {
    // Sphere B (r = 10) overlaps sphere A (r = 8) by 4 mm along x.
    const Vec3 ca{0, 0, 0}, cb{14, 0, 0};
    SurfaceScene scene({geodesicSphere(16, 8, ca), geodesicSphere(16, 10, cb)});
    ASSERT_TRUE(scene.closed(0));
    ASSERT_TRUE(scene.closed(1));
    const std::vector<SurfaceSample> samples = allSamples(scene, 256);
    ClosestPrimitiveKernel kernel(runtime(), scene);
    const auto device = kernel.run(samples);
    // The mesh is within sagitta s of the true sphere, so distances agree
    // with the analytic ones to about s (r·(1 - cos(edge angle / 2))).
    const double sagitta = 10 * (1 - std::cos(0.5 * 1.1071 / 16)) * 2;
    std::size_t inside = 0;
    for (std::size_t k = 0; k < samples.size(); ++k) {
        const Vec3 p = samples[k].point;
        const Vec3 other = samples[k].object == 0 ? cb : ca;
        const double r = samples[k].object == 0 ? 10 : 8;
        const double analytic = length(p - other) - r;
        EXPECT_EQ(device[k].object, samples[k].object == 0 ? 1 : 0);
        EXPECT_NEAR(device[k].distanceMm, analytic, sagitta) << "sample " << k;
        if (std::abs(analytic) > sagitta) {
            EXPECT_EQ(device[k].distanceMm < 0, analytic < 0);
        }
        inside += device[k].distanceMm < 0;
    }
    EXPECT_GT(inside, 100u);
}

TEST(ClosestPrimitives, BandAndTargetQueriesAgreeWithBruteForce) {
    std::mt19937 random(5);
    SurfaceScene scene({geodesicSphere(8, 6), boxMesh({9, -4, -4}, {15, 4, 4}, 4),
                        randomSoup(random, {0, 14, 0}, 100)});
    const std::vector<SurfaceSample> samples = allSamples(scene, 64);
    ClosestPrimitiveKernel kernel(runtime(), scene);
    for (const DistanceQuery& query :
         {DistanceQuery{-1, 5.0}, DistanceQuery{1, INFINITY}, DistanceQuery{2, 7.5}}) {
        const auto brute = closestPrimitivesBruteForce(scene, samples, query);
        expectSameAnswers(scene, samples, closestPrimitivesReference(scene, samples, query), brute,
                          1e-12, query);
        expectSameAnswers(scene, samples, kernel.run(samples, query), brute,
                          std::max(kernel.toleranceMm(), 1e-12), query);
        std::size_t none = 0;
        for (std::size_t k = 0; k < brute.size(); ++k) {
            if (brute[k].object < 0) {
                ++none;
                continue;
            }
            EXPECT_LT(std::abs(brute[k].distanceMm), query.maxDistanceMm);
            if (query.target >= 0) {
                EXPECT_EQ(brute[k].object, query.target);
            }
        }
        if (std::isfinite(query.maxDistanceMm)) {
            EXPECT_GT(none, 0u);
        }
    }
}

TEST(ClosestPrimitives, RealMeshesAgreeWithBruteForce) {
    const std::filesystem::path meshes = std::filesystem::path(DFRECON_FIXTURES) / "meshes";
    ASSERT_TRUE(std::filesystem::exists(meshes / "eight.off")) << "run `make setup`";
    // CGAL's eight and sphere, scaled to a few cm and placed close together.
    auto place = [](TriangleSoup soup, double scale, Vec3 offset) {
        for (Vec3& p : soup.points) p = offset + scale * p;
        return soup;
    };
    SurfaceScene scene({place(readTriangleSoup((meshes / "eight.off").string()), 40, {0, 0, 0}),
                        place(readTriangleSoup((meshes / "sphere.off").string()), 12, {25, 5, 0})});
    EXPECT_TRUE(scene.closed(0));
    EXPECT_TRUE(scene.closed(1));
    const std::vector<SurfaceSample> samples = allSamples(scene, 96);
    const auto brute = closestPrimitivesBruteForce(scene, samples);
    ClosestPrimitiveKernel kernel(runtime(), scene);
    expectSameAnswers(scene, samples, kernel.run(samples), brute,
                      std::max(kernel.toleranceMm(), 1e-12));
}

TEST(ClosestPrimitives, SamplesOffTheirTrianglesAreSearchedInFull) {
    // The candidates of a source triangle hold for points on it; callers
    // may pass any point with any triangle, and those must not be culled.
    std::mt19937 random(3);
    SurfaceScene scene({geodesicSphere(8, 6), randomSoup(random, {14, 0, 0}, 200)});
    std::vector<SurfaceSample> samples = allSamples(scene, 48);
    std::uniform_real_distribution<double> offset(-3, 3);
    for (std::size_t k = 0; k < samples.size(); k += 2)
        samples[k].point = samples[k].point + Vec3{offset(random), offset(random), offset(random)};
    const auto brute = closestPrimitivesBruteForce(scene, samples);
    expectSameAnswers(scene, samples, closestPrimitivesReference(scene, samples), brute, 1e-12);
    ClosestPrimitiveKernel kernel(runtime(), scene);
    expectSameAnswers(scene, samples, kernel.run(samples), brute,
                      std::max(kernel.toleranceMm(), 1e-12));
}

TEST(ClosestPrimitives, TrianglesWithManyEquallyNearCandidatesSearchInFull) {
    // A small soup at the centre of a fine sphere: every sphere triangle is
    // about equally near, far more than a source triangle lists, so its
    // samples take the full search; the sphere's samples take the lists.
    std::mt19937 random(9);
    TriangleSoup centre = randomSoup(random, {0, 0, 0}, 20);
    for (Vec3& p : centre.points) p = 0.1 * p;
    SurfaceScene scene({geodesicSphere(16, 10), centre});
    const std::vector<SurfaceSample> samples = allSamples(scene, 96);
    const auto brute = closestPrimitivesBruteForce(scene, samples);
    expectSameAnswers(scene, samples, closestPrimitivesReference(scene, samples), brute, 1e-12);
    ClosestPrimitiveKernel kernel(runtime(), scene);
    expectSameAnswers(scene, samples, kernel.run(samples), brute,
                      std::max(kernel.toleranceMm(), 1e-12));
    // Both ways ran: every sampled triangle has a list or overflowed.
    const CullStats cull = kernel.lastCullStats();
    EXPECT_EQ(cull.sources, scene.object(0).triangles.size() + scene.object(1).triangles.size());
    EXPECT_GT(cull.overflowing, 0u);
    EXPECT_LT(cull.overflowing, cull.sources);
}
