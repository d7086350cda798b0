// The slabs of one ROI are built on the cores left free and appended in
// order (recon/ParallelSlabs buildSlabs): the surface must be the one a
// single core builds, point for point and triangle for triangle, with the
// same counts. The single-core run holds every core of the process's budget
// (geometry/CoreBudget), so the reconstruction gets no helper thread.
#include <gtest/gtest.h>

#include <string>
#include <thread>

#include "geometry/CoreBudget.hpp"
#include "io/labels/MaskContours.hpp"
#include "recon/Reconstruction.hpp"
#include "shapes/RandomLabelVolumes.hpp"
#include "tests/CpuRuntime.hpp"

namespace dfrecon {
namespace {

Reconstruction onOneCore(const Roi& roi, const ReconstructionOptions& options) {
    const CoreLease everyCore(std::max(1u, std::thread::hardware_concurrency()));
    return reconstructSurface(cpuRuntime(), roi, options);
}

void expectSameSurface(const Reconstruction& one, const Reconstruction& many,
                       const std::string& name) {
    SCOPED_TRACE(name);
    ASSERT_EQ(one.surface.points.size(), many.surface.points.size());
    ASSERT_EQ(one.surface.triangles.size(), many.surface.triangles.size());
    for (std::size_t v = 0; v < one.surface.points.size(); ++v)
        ASSERT_TRUE(one.surface.points[v] == many.surface.points[v]) << "point " << v;
    EXPECT_TRUE(one.surface.triangles == many.surface.triangles);
    EXPECT_EQ(one.check.validSolid(), many.check.validSolid());
    EXPECT_EQ(one.check.volumeMm3, many.check.volumeMm3);
    EXPECT_EQ(one.stats.strips, many.stats.strips);
    EXPECT_EQ(one.stats.rejectedStrips, many.stats.rejectedStrips);
    EXPECT_EQ(one.stats.recursions, many.stats.recursions);
    EXPECT_EQ(one.stats.deepestLevel, many.stats.deepestLevel);
    EXPECT_EQ(one.stats.limitClosings, many.stats.limitClosings);
    EXPECT_EQ(one.stats.caps, many.stats.caps);
    EXPECT_EQ(one.stats.fallbackSlabs, many.stats.fallbackSlabs);
    EXPECT_EQ(one.stats.repairedPieces, many.stats.repairedPieces);
}

TEST(ParallelSlabs, SeveralCoresBuildWhatOneCoreBuilds) {
    if (std::thread::hardware_concurrency() < 2)
        GTEST_SKIP() << "one hardware thread: the slabs cannot run on several cores";
    // Blobs that merge, branch and end between planes (slabs recursing,
    // closed by prisms, capped inside), smooth and linear; and a hostile
    // label volume's ROIs (touching and nested contours).
    std::vector<Roi> rois = contoursFromLabels(manyBlobLabelVolume(5, 40, 120, 12)).rois;
    for (Roi& roi : contoursFromLabels(hostileLabelVolume(7)).rois) rois.push_back(std::move(roi));
    std::size_t compared = 0;
    for (const Roi& roi : rois) {
        if (roi.slices.size() < 3) continue;
        for (const Interpolation interpolation : {Interpolation::Smooth, Interpolation::Linear}) {
            ReconstructionOptions options;
            options.interpolation = interpolation;
            const Reconstruction one = onOneCore(roi, options);
            const Reconstruction many = reconstructSurface(cpuRuntime(), roi, options);
            ++compared;
            expectSameSurface(
                one, many,
                roi.name + (interpolation == Interpolation::Smooth ? " smooth" : " linear"));
        }
    }
    EXPECT_GE(compared, 2u);
}

}  // namespace
}  // namespace dfrecon
