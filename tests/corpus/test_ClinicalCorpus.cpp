// The clinical corpus (tests/corpus/ClinicalCorpus): each case written as an
// RTSTRUCT and read back as a user's file is, every ROI with contours
// reconstructed at default settings. Each must be a valid closed solid (its
// check as written, floats in patient coordinates) through every contour
// point as read, with the volume planning systems count for it within a few
// per cent. Seeds 0 .. DFRECON_CORPUS_SEEDS - 1 of every kind (default 3;
// the long run in docs/building.md, "The clinical corpus", takes 1000);
// DFRECON_CORPUS_FIRST_SEED
// moves the window.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <tuple>

#include "dfrecon/Contours.hpp"
#include "dfrecon/Reconstruct.hpp"
#include "io/dicom/RtStruct.hpp"
#include "tests/CpuRuntime.hpp"
#include "tests/corpus/ClinicalCorpus.hpp"

namespace dfrecon::testing {
namespace {

std::uint32_t environmentNumber(const char* name, std::uint32_t fallback) {
    const char* value = std::getenv(name);
    return value && *value ? std::uint32_t(std::strtoul(value, nullptr, 10)) : fallback;
}

using FloatPoint = std::tuple<float, float, float>;

FloatPoint asWritten(const Vec3& p) {
    return {float(p.x), float(p.y), float(p.z)};
}

// What the case must give, ROI by ROI; a message for each failure.
void expectEveryRoiASolid(CorpusKind kind, std::uint32_t seed) {
    // DFRECON_CORPUS_KEEP=DIR keeps every case's file there, to look at.
    const char* keep = std::getenv("DFRECON_CORPUS_KEEP");
    const std::string path =
        ((keep && *keep ? std::filesystem::path(keep) : std::filesystem::temp_directory_path()) /
         ("corpus-" + std::to_string(int(kind)) + "-" + std::to_string(seed) + ".dcm"))
            .string();
    writeRtStruct(clinicalCase(kind, seed), path);
    const ContoursRead read = readContours(path);
    if (!keep || !*keep) std::filesystem::remove(path);
    for (const Roi& roi : read.contours.rois) {
        SCOPED_TRACE("seed " + std::to_string(seed) + ", ROI '" + roi.name + "'");
        ASSERT_FALSE(roi.defect.has_value()) << roi.defect->what();
        ASSERT_FALSE(roi.slices.empty());
        const RoiSurface result = reconstructRoi(cpuRuntime(), roi, {});
        ASSERT_TRUE(result.check.validSolid())
            << "intersecting pairs " << result.check.intersectingPairs << ", boundary edges "
            << result.check.boundaryEdges << ", non-manifold edges "
            << result.check.nonManifoldEdges << ", degenerate " << result.check.degenerateTriangles;
        // Every contour point as read is a vertex (as the file holds it),
        // but for the few moved a micrometre where contours of a plane
        // touched.
        // An oblique stack's points are rounded to float in their plane
        // frame before they are turned into patient coordinates and rounded
        // again: there they are vertices to float precision.
        const bool axial = roi.frame.isIdentity();
        std::set<FloatPoint> vertices;
        for (const Vec3& p : result.surface.points) vertices.insert(asWritten(p));
        auto isVertex = [&](const Vec3& p) {
            if (axial) return vertices.count(asWritten(p)) > 0;
            // Two roundings to float: within two float steps of the largest
            // coordinate.
            const float tolerance =
                float(3e-7 * (1 + std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)})));
            const FloatPoint q = asWritten(p);
            for (auto it = vertices.lower_bound({std::get<0>(q) - tolerance, -1e30f, -1e30f});
                 it != vertices.end() && std::get<0>(*it) <= std::get<0>(q) + tolerance; ++it)
                if (std::abs(std::get<1>(*it) - std::get<1>(q)) <= tolerance &&
                    std::abs(std::get<2>(*it) - std::get<2>(q)) <= tolerance)
                    return true;
            return false;
        };
        std::size_t missing = 0, points = 0;
        for (const Slice& slice : roi.slices)
            for (const Polygon& contour : slice.contours)
                for (const Point2 p : contour) {
                    ++points;
                    missing += !isVertex(roi.frame.toPatient({p.x, p.y, slice.zMm}));
                }
        EXPECT_LE(missing, 2 * result.stats.touchesOpened) << "of " << points << " points";
        // The planning system's Σ area × thickness: within 10 % from 1 cc up
        // (the surface bulges between planes where contours change), 30 %
        // below (a few planes of a few points).
        const double contourMm3 = result.contourVolumeMm3;
        ASSERT_GT(contourMm3, 0);
        const double off = std::abs(result.check.volumeMm3 / contourMm3 - 1);
        EXPECT_LT(off, contourMm3 >= 1000 ? 0.10 : 0.30)
            << result.check.volumeMm3 << " mm³ against " << contourMm3 << " mm³";
    }
}

class ClinicalCorpus : public ::testing::TestWithParam<std::pair<CorpusKind, const char*>> {};

TEST_P(ClinicalCorpus, EveryRoiIsAValidSolidThroughItsContours) {
    const std::uint32_t first = environmentNumber("DFRECON_CORPUS_FIRST_SEED", 0);
    const std::uint32_t seeds = environmentNumber("DFRECON_CORPUS_SEEDS", 3);
    for (std::uint32_t seed = first; seed < first + seeds; ++seed) {
        expectEveryRoiASolid(GetParam().first, seed);
        if (HasFatalFailure()) return;
    }
}

INSTANTIATE_TEST_SUITE_P(Kinds, ClinicalCorpus, ::testing::ValuesIn(kCorpusKinds),
                         [](const auto& info) { return std::string(info.param.second); });

// What the generators are for: each kind holds what it says it holds,
// checked on what reading reports.
TEST(ClinicalCorpus, EachKindHoldsWhatPlanningSystemsDraw) {
    auto readCase = [](CorpusKind kind, std::uint32_t seed) {
        const std::string path = (std::filesystem::temp_directory_path() /
                                  ("dfrecon-corpus-kind-" + std::to_string(int(kind)) + ".dcm"))
                                     .string();
        writeRtStruct(clinicalCase(kind, seed), path);
        ContoursRead read = readContours(path);
        std::filesystem::remove(path);
        return read;
    };
    PlaneReadingCounts crossing, twice;
    std::size_t gaps = 0, holes = 0;
    for (std::uint32_t seed = 0; seed < 4; ++seed) {
        for (const Roi& roi : readCase(CorpusKind::CrossingOutlines, seed).contours.rois)
            crossing += roi.reading;
        for (const Roi& roi : readCase(CorpusKind::StoredTwice, seed).contours.rois)
            twice += roi.reading;
        for (const Roi& roi : readCase(CorpusKind::PlanesLeftEmpty, seed).contours.rois)
            gaps += roi.restartsAt.size();
        for (const Roi& roi : readCase(CorpusKind::VesselHoles, seed).contours.rois)
            for (const Slice& slice : roi.slices)
                for (const Polygon& c : slice.contours) holes += signedArea(c) < 0;
    }
    EXPECT_GT(crossing.resolvedContours, 0u);
    EXPECT_GT(crossing.foldPoints, 0u);
    EXPECT_GT(twice.duplicateContours, 20u);
    EXPECT_GT(gaps, 4u);
    EXPECT_GT(holes, 40u);
}

}  // namespace
}  // namespace dfrecon::testing
