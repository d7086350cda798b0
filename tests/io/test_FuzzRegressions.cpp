// Inputs the fuzzers found or started from: each must load or fail with an
// InputError, never crash, hang or throw anything else. tests/data/fuzz/
// holds .slices inputs; tests/data/fuzz-rtstruct/ (seeds) and
// tests/data/fuzz-rtstruct-regressions/ (findings) hold RTSTRUCT inputs.
#include <gtest/gtest.h>

#include <filesystem>

#include "io/RtStruct.hpp"
#include "io/SlicesFile.hpp"

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
