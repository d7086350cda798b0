// Inputs the fuzzers found or started from: each must load or fail with an
// InputError, never crash, hang or throw anything else. tests/data/fuzz/
// holds .slices inputs; tests/data/fuzz-rtstruct/ (seeds) and
// tests/data/fuzz-rtstruct-regressions/ (findings) hold RTSTRUCT inputs;
// tests/data/fuzz-mesh*/ and tests/data/fuzz-label*/ hold mesh files and
// label volumes, stored as files of their format (the fuzz targets' first
// byte, which picks the extension, taken off and made the extension).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <vector>

#include "io/contours/SlicesFile.hpp"
#include "io/dicom/RtStruct.hpp"
#include "io/files/InputLimits.hpp"
#include "io/labels/LabelVolume.hpp"
#include "io/mesh/MeshIO.hpp"

using namespace dfrecon;
namespace fs = std::filesystem;

TEST(FuzzRegressions, EveryKeptInputIsHandled) {
    const fs::path dir = fs::path(DFRECON_TEST_DATA) / "fuzz";
    int files = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (!entry.is_regular_file()) continue;
        ++files;
        try {
            readSlicesFile(entry.path().string());
        } catch (const InputError&) {
            // A clear error is the expected outcome for most of these.
        }
    }
    EXPECT_GT(files, 0);
}

TEST(FuzzRegressions, EveryKeptRtStructIsHandled) {
    // The limits of tests/fuzz/fuzz_rtstruct.cpp, so that an input kept for
    // tripping one of them still does here.
    RtStructLimits limits;
    limits.maxRois = 64;
    limits.maxContoursPerRoi = 2000;
    limits.maxPointsTotal = 50'000;
    const fs::path written = fs::temp_directory_path() / "dfrecon-test-fuzz-rtstruct.dcm";
    int files = 0;
    for (const char* name : {"fuzz-rtstruct", "fuzz-rtstruct-regressions"}) {
        const fs::path dir = fs::path(DFRECON_TEST_DATA) / name;
        if (!fs::is_directory(dir)) continue;
        for (const auto& entry : fs::directory_iterator(dir)) {
            if (!entry.is_regular_file()) continue;
            ++files;
            SCOPED_TRACE(entry.path().string());
            RtStructLoad load;
            try {
                load = readRtStruct(entry.path().string(), limits);
            } catch (const InputError&) {
                continue;  // a clear error is the expected outcome for most
            }
            if (load.contours.rois.empty()) continue;  // nothing writeRtStruct can write
            // What loads writes and reads back with the same shape (the
            // fuzz target compares every point).
            writeRtStruct(load.contours, written.string());
            const RtStructLoad back = readRtStruct(written.string(), limits);
            ASSERT_EQ(back.contours.rois.size(), load.contours.rois.size());
            for (std::size_t r = 0; r < load.contours.rois.size(); ++r) {
                EXPECT_EQ(back.contours.rois[r].slices.size(), load.contours.rois[r].slices.size());
                EXPECT_EQ(back.contours.rois[r].contourCount(),
                          load.contours.rois[r].contourCount());
                EXPECT_EQ(back.contours.rois[r].pointCount(), load.contours.rois[r].pointCount());
            }
        }
    }
    fs::remove(written);
    EXPECT_GT(files, 0);
}

namespace {

// The regular files of tests/data/NAME/ for each NAME, seeds and findings.
std::vector<fs::path> keptInputs(std::initializer_list<const char*> names) {
    std::vector<fs::path> files;
    for (const char* name : names) {
        const fs::path dir = fs::path(DFRECON_TEST_DATA) / name;
        if (!fs::is_directory(dir)) continue;
        for (const auto& entry : fs::directory_iterator(dir))
            if (entry.is_regular_file()) files.push_back(entry.path());
    }
    return files;
}

}  // namespace

TEST(FuzzRegressions, EveryKeptMeshIsHandled) {
    const std::vector<fs::path> files = keptInputs({"fuzz-mesh", "fuzz-mesh-regressions"});
    for (const fs::path& file : files) {
        SCOPED_TRACE(file.string());
        TriangleSoup soup;
        try {
            soup = readTriangleSoup(file.string());
        } catch (const InputError&) {
            continue;  // a clear error is the expected outcome for most
        }
        // What tests/fuzz/fuzz_mesh.cpp checks of whatever loads.
        EXPECT_FALSE(soup.triangles.empty());
        for (const Vec3& p : soup.points)
            for (double c : {p.x, p.y, p.z})
                ASSERT_TRUE(std::isfinite(c) && std::abs(c) <= kMaxAbsCoordinateMm);
        for (const auto& triangle : soup.triangles)
            for (std::uint32_t v : triangle) ASSERT_LT(v, soup.points.size());
    }
    EXPECT_GT(files.size(), 0u);
}

TEST(FuzzRegressions, EveryKeptLabelVolumeIsHandled) {
    const std::vector<fs::path> files = keptInputs({"fuzz-label", "fuzz-label-regressions"});
    for (const fs::path& file : files) {
        SCOPED_TRACE(file.string());
        LabelVolume volume;
        try {
            volume = readLabelVolume(file.string());
        } catch (const InputError&) {
            continue;
        }
        // What tests/fuzz/fuzz_label_volume.cpp checks of whatever loads.
        const VolumeGeometry& g = volume.geometry;
        for (int a = 0; a < 3; ++a) {
            EXPECT_GT(g.size[a], 0);
            EXPECT_TRUE(std::isfinite(g.spacingMm[a]) && g.spacingMm[a] >= kMinVoxelSpacingMm);
            EXPECT_TRUE(std::isfinite(g.originMm[a]));
        }
        EXPECT_EQ(volume.labels.size(), g.voxelCount());
        for (int corner = 0; corner < 8; ++corner) {
            auto at = [&](int a) { return (corner >> a & 1) ? g.size[a] - 0.5 : -0.5; };
            const Vec3 p = g.worldOfIndex(at(0), at(1), at(2));
            for (double c : {p.x, p.y, p.z})
                EXPECT_TRUE(std::isfinite(c) && std::abs(c) <= kMaxAbsCoordinateMm);
        }
    }
    EXPECT_GT(files.size(), 0u);
}
