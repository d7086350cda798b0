// dfrecon margin, combine and histogram as a user runs them: outputs that
// read back (info, reconstruct) with the new ROI named and typed, RTSTRUCTs
// that dciodvfy accepts, exit codes and messages for bad expressions and
// options, and reports that agree with the geometry (a sphere's margin, a
// ring's volume, an OVH's ends).
#include "tests/SyntheticDicomSeries.hpp"  // DCMTK first

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/CliRun.hpp"
#include "tests/TempDir.hpp"

namespace fs = std::filesystem;
using dfrecon::testing::CliResult;
using dfrecon::testing::runCli;
using dfrecon::testing::runShell;
using dfrecon::testing::TempDir;

namespace {

// A sphere of radius 20 mm on planes 2 mm apart (synth), its contours of
// 64 points; the margins below use a 0.5 mm lattice: small enough that
// the sanitizer build runs these in seconds.
std::string sphereSlices(const TempDir& dir) {
    const std::string path = dir / "sphere.slices";
    const CliResult r = runCli(dir.str(), "synth sphere --spacing 2 --points 64 -o " + path);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return path;
}

}  // namespace

TEST(CliAlgebra, MarginWritesTheNewRoiIntoTheStructureSet) {
    TempDir dir("cli-margin");
    const std::string in = sphereSlices(dir), out = dir / "grown.dcm";
    const CliResult r = runCli(dir.str(), "-q margin --step 0.5 " + in +
                                              " --roi sphere --mm 5 --name PTV --roi-type PTV "
                                              "--colour 255,0,0 --mesh " +
                                              (dir / std::string("ptv.ply")) + " --json -o " + out);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json report = nlohmann::json::parse(r.out);
    EXPECT_EQ(report["roi"], "PTV");
    // A ball of 25 mm: 65.45 cc; the sections are exact on the planes.
    const double exact = 4.0 / 3 * M_PI * 25 * 25 * 25 / 1000;
    EXPECT_NEAR(report["mesh"]["volumeCc"].get<double>(), exact, 0.01 * exact);
    EXPECT_TRUE(report["mesh"]["validSolid"].get<bool>());
    EXPECT_GT(report["planes"].get<int>(), 20);  // continued beyond the sphere's planes

    const CliResult info = runCli(dir.str(), "info " + out + " --json");
    ASSERT_EQ(info.exitCode, 0) << info.err;
    const nlohmann::json rois = nlohmann::json::parse(info.out)["rois"];
    ASSERT_EQ(rois.size(), 2u);
    EXPECT_EQ(rois[1]["name"], "PTV");
    if (std::system("command -v dciodvfy >/dev/null 2>&1") == 0) {
        const CliResult v =
            runShell(dir.str(), "dciodvfy " + out + " 2>&1 | grep -c '^Error' || true");
        EXPECT_EQ(std::stoi(v.out), 0) << v.out;
    }
    // The name is taken now.
    const CliResult again =
        runCli(dir.str(), "-q margin --step 0.5 " + out + " --roi sphere --mm 5 --name PTV -o " +
                              (dir / std::string("again.dcm")));
    EXPECT_EQ(again.exitCode, 1);
    EXPECT_NE(again.err.find("--replace"), std::string::npos) << again.err;
}

TEST(CliAlgebra, CombineEvaluatesRingsAndRefusesBadExpressions) {
    TempDir dir("cli-combine");
    const std::string in = sphereSlices(dir), out = dir / "ring.slices";
    const CliResult r =
        runCli(dir.str(),
               "-q combine --step 0.5 " + in +
                   " --expr \"Ring = (sphere + 10) - (sphere + 3)\" --json --only-new -o " + out);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json report = nlohmann::json::parse(r.out);
    const double exact = 4.0 / 3 * M_PI * (30.0 * 30 * 30 - 23.0 * 23 * 23) / 1000;
    EXPECT_NEAR(report["contourVolumeCc"].get<double>(), exact, 0.02 * exact);
    const CliResult back = runCli(
        dir.str(), "-q reconstruct " + out + " --roi Ring -o " + (dir / std::string("ring.ply")));
    EXPECT_EQ(back.exitCode, 0) << back.err;

    const struct {
        const char* expression;
        const char* message;
    } bad[] = {{"Ring = (sphere + 10", "column 20: expected ')'"},
               {"X = spher + 3", "no ROI named 'spher'"},
               {"X = (sphere - sphere) + 3", "name the difference first"},
               {"sphere + 3", "NAME = EXPRESSION"}};
    for (const auto& b : bad) {
        const CliResult e =
            runCli(dir.str(), "-q combine --step 0.5 " + in + " --expr \"" + b.expression +
                                  "\" -o " + (dir / std::string("x.slices")));
        EXPECT_EQ(e.exitCode, 1) << b.expression << ": " << e.err;
        EXPECT_NE(e.err.find(b.message), std::string::npos) << e.err;
        EXPECT_FALSE(fs::exists(dir / std::string("x.slices")));
    }
    const CliResult mixed =
        runCli(dir.str(), "-q margin --step 0.5 " + in +
                              " --roi sphere --mm-per-direction 5,-3,5,5,5,5 -o " +
                              (dir / std::string("x.slices")));
    EXPECT_EQ(mixed.exitCode, 1);
    EXPECT_NE(mixed.err.find("both grows and shrinks"), std::string::npos) << mixed.err;
    // Eight octants: 5 mm everywhere but 2 mm posterior (+y).
    const CliResult octants =
        runCli(dir.str(), "-q margin --step 0.5 " + in +
                              " --roi sphere --mm-per-direction 5,5,5,2,5,5 --json --only-new -o " +
                              (dir / std::string("o.slices")));
    ASSERT_EQ(octants.exitCode, 0) << octants.err;
    const CliResult info = runCli(dir.str(), "info --slices " + (dir / std::string("o.slices")));
    EXPECT_NE(info.out.find("y -24.97"), std::string::npos) << info.out;  // 5 mm anterior,
    EXPECT_NE(info.out.find(".. 21.97"), std::string::npos) << info.out;  // 2 mm posterior
    EXPECT_NE(info.out.find("24 slices, 24 contours"), std::string::npos) << info.out;
}

TEST(CliAlgebra, HistogramWritesTableAndPlot) {
    TempDir dir("cli-histogram");
    const std::string in = sphereSlices(dir);
    const std::string two = dir / "two.slices";
    ASSERT_EQ(runCli(dir.str(), "-q combine --step 0.5 " + in +
                                    " --expr \"Shell = (sphere + 6) - (sphere + 2)\" -o " + two)
                  .exitCode,
              0);
    const CliResult r =
        runCli(dir.str(), "-q histogram --step 1 --surface-spacing 1 " + two +
                              " --roi Shell --to sphere --json -o " + (dir / std::string("h.csv")) +
                              " --plot " + (dir / std::string("h.png")));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json report = nlohmann::json::parse(r.out);
    // The shell lies 2 to 6 mm from the sphere.
    EXPECT_NEAR(report["volume"]["minMm"].get<double>(), 2, 0.3);
    EXPECT_NEAR(report["volume"]["maxMm"].get<double>(), 6, 0.3);
    EXPECT_EQ(report["volume"]["fractionInsideTarget"].get<double>(), 0.0);
    EXPECT_EQ(report["volumeStepMm"].get<double>(), 1.0);  // within the budget: as asked
    EXPECT_EQ(report["surfaceSpacingMm"].get<double>(), 1.0);
    EXPECT_TRUE(fs::file_size(dir / std::string("h.png")) > 1000);
    std::ifstream csv(dir / std::string("h.csv"));
    std::string header;
    std::getline(csv, header);
    EXPECT_EQ(header, "distance_mm,overlap_volume_fraction,overlap_volume_cc,surface_fraction");
}

TEST(CliAlgebra, LikeACtPutsTheNewRoiOnItsImagePlanes) {
    TempDir dir("cli-margin-like");
    const std::string in = sphereSlices(dir), ct = dir / "ct";
    fs::create_directories(ct);
    // 1.25 mm apart from z = -40: the grown sphere (|z| ≤ 25) spans 40 of them.
    dfrecon::testing::writeSyntheticSeries(ct, 65, -40, 1.25);
    const std::string out = dir / "like.dcm";
    const CliResult r =
        runCli(dir.str(), "-q margin --step 0.5 " + in + " --roi sphere --mm 5 --like " + ct +
                              " --only-new --json -o " + out);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json report = nlohmann::json::parse(r.out);
    EXPECT_EQ(report["planesWithContours"].get<int>(), 39);  // |z| < 25 exactly: -23.75 .. 23.75
    const CliResult slices = runCli(dir.str(), "info " + out + " --slices");
    ASSERT_EQ(slices.exitCode, 0) << slices.err;
    EXPECT_NE(slices.out.find("z    -23.75"), std::string::npos) << slices.out;
    EXPECT_NE(slices.out.find("spacing uniform 1.25 mm"), std::string::npos) << slices.out;
}
