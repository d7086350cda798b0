// The dfrecon program as a user runs it: exit codes, file:line messages,
// reports, help texts, and no output left behind by a failed run.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "io/contours/SlicesFile.hpp"
#include "io/dicom/RtStruct.hpp"
#include "io/labels/LabelInput.hpp"
#include "io/labels/LabelVolume.hpp"
#include "io/mesh/MeshIO.hpp"
#include "shapes/MeshShapes.hpp"
#include "shapes/RandomLabelVolumes.hpp"
#include "tests/BadSlicesInputs.hpp"
#include "tests/CliRun.hpp"
#include "tests/TempDir.hpp"
#include "tests/VtkRead.hpp"

namespace fs = std::filesystem;

namespace {

using Result = dfrecon::testing::CliResult;
using dfrecon::testing::slurp;

fs::path scratch() {
    return dfrecon::testing::processScratch("test-cli");
}

Result runDfrecon(const std::string& args) {
    return dfrecon::testing::runCli(scratch().string(), args);
}

}  // namespace

TEST(Cli, EveryMalformedInputExitsTwoWithFileAndLine) {
    for (const auto& input : dfrecon::testing::badInputs()) {
        const fs::path file = scratch() / (std::string(input.name) + ".slices");
        std::ofstream(file, std::ios::binary) << input.text;
        const Result run = runDfrecon("info " + file.string());
        EXPECT_EQ(run.exitCode, 2) << input.name << ": " << run.err;
        const std::string where =
            file.string() + (input.line > 0 ? ":" + std::to_string(input.line) : "") + ": ";
        EXPECT_NE(run.err.find(where), std::string::npos) << input.name << ": " << run.err;
        EXPECT_NE(run.err.find(input.message), std::string::npos) << input.name << ": " << run.err;
        // A file that cannot be read prints nothing; one whose ROI is
        // broken lists its ROIs, that one NOT READ.
        EXPECT_TRUE(run.out.empty() || run.out.find("NOT READ") != std::string::npos)
            << input.name << ": " << run.out;
    }
}

// A bow tie on the middle plane is read as planning systems read it: the
// two triangles of its even-odd region, one warning for the ROI at its
// line, the change in contourReading, and the ROI reconstructs into a valid
// solid. The former --repair-contours flag is still accepted.
TEST(Cli, SelfCrossingContourIsReadByTheEvenOddRule) {
    const fs::path file = scratch() / "bow-tie.slices", mesh = scratch() / "bow-tie.ply";
    std::ofstream(file) << "dfrecon-slices 1\nunits mm\nroi tie\n"
                           "slice 0\ncontour 4\n0 0\n10 0\n10 10\n0 10\n"
                           "slice 2\ncontour 4\n0 0\n10 10\n10 0\n0 10\n"
                           "slice 4\ncontour 4\n0 0\n10 0\n10 10\n0 10\n";
    for (const std::string flag : {"", "--repair-contours "}) {
        const Result run =
            runDfrecon(flag + "reconstruct --json " + file.string() + " -o " + mesh.string());
        ASSERT_EQ(run.exitCode, 0) << run.err;
        EXPECT_NE(run.err.find(file.string() + ":3: warning: ROI 'tie' read as planning systems"),
                  std::string::npos)
            << run.err;
        const auto report = nlohmann::json::parse(run.out)["rois"][0];
        EXPECT_TRUE(report["validSolid"].get<bool>());
        EXPECT_EQ(report["contourReading"]["resolvedContours"], 1);
        EXPECT_EQ(report["contourReading"]["rule"], "even-odd");
        // Planes 0 and 4 hold 100 mm², plane 2 the two triangles' 50 mm²;
        // each plane stands for 2 mm (an end plane takes its one gap).
        EXPECT_NEAR(report["contourVolumeMm3"].get<double>(), (100 + 50 + 100) * 2.0, 1e-9);
    }
}

// An ROI with planes left empty (other ROIs have contours there) ends and
// starts again: two closed pieces, its volume the planning system's sum over
// its planes (the gap counts nothing), and a warning naming the gap.
TEST(Cli, AnRoiWithPlanesLeftEmptyIsTwoPieces) {
    const fs::path file = scratch() / "gap.slices", dir = scratch() / "gap";
    std::string text = "dfrecon-slices 1\nunits mm\nroi Body\n";
    const std::string big = "contour 4\n-20 -20\n20 -20\n20 20\n-20 20\n";
    const std::string small = "contour 4\n0 0\n10 0\n10 10\n0 10\n";
    for (int z = 0; z <= 20; z += 2) text += "slice " + std::to_string(z) + "\n" + big;
    text += "roi Node\n";
    for (int z : {2, 4, 6, 14, 16}) text += "slice " + std::to_string(z) + "\n" + small;
    std::ofstream(file) << text;
    const Result run = runDfrecon("reconstruct --all --json --interpolation linear " +
                                  file.string() + " -o " + dir.string());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_NE(run.err.find("ROI 'Node' has planes left empty between 6 to 14 mm"),
              std::string::npos)
        << run.err;
    const auto node = nlohmann::json::parse(run.out)["rois"][1];
    EXPECT_TRUE(node["validSolid"].get<bool>());
    EXPECT_EQ(node["pieces"], 2);
    EXPECT_EQ(node["components"], 2);
    EXPECT_EQ(node["planesLeftEmptyMm"], nlohmann::json::parse("[[6.0, 14.0]]"));
    // Planes 2-6 stand for 6 mm, planes 14-16 for 4 mm; flat caps half a gap
    // beyond each end make straight prisms hold exactly that.
    EXPECT_NEAR(node["contourVolumeMm3"].get<double>(), 100 * (6 + 4), 1e-9);
    EXPECT_NEAR(node["volumeMm3"].get<double>(), 100 * (6 + 4), 1e-3);
}

// Two labels of a voxelised ball, touching on every plane: --neighbours
// report measures their overlap between the planes, apart moves them out of
// each other (the files written as moved, still valid), independent (the
// default) says nothing of neighbours.
TEST(Cli, NeighboursAreReportedAndKeptApart) {
    const std::string slices = std::string(DFRECON_TEST_DATA) + "/neighbours/split-ball.slices";
    auto neighbours = [&](const std::string& mode) {
        const fs::path dir = scratch() / ("split-" + mode);
        const Result run = runDfrecon("reconstruct --all --json --neighbours " + mode + " " +
                                      slices + " -o " + dir.string());
        EXPECT_EQ(run.exitCode, 0) << run.err;
        return nlohmann::json::parse(run.out);
    };
    const auto independent = neighbours("independent");
    EXPECT_TRUE(independent["neighbours"].is_null());
    const auto reported = neighbours("report")["neighbours"];
    const auto apart = neighbours("apart");
    ASSERT_EQ(reported["pairs"].size(), 1u);
    ASSERT_EQ(apart["neighbours"]["pairs"].size(), 1u);
    const double before = reported["pairs"][0]["overlapMm3"].get<double>();
    const double after = apart["neighbours"]["pairs"][0]["overlapMm3"].get<double>();
    EXPECT_GT(before, 1.0);
    EXPECT_LT(after, 0.1 * before);
    EXPECT_EQ(reported["pairs"][0]["verticesMovedA"], 0);
    EXPECT_GT(apart["neighbours"]["pairs"][0]["verticesMovedA"].get<int>(), 0);
    for (const auto& roi : apart["rois"]) {
        EXPECT_TRUE(roi["validSolid"].get<bool>());
        // The report's volume is the moved surface's, as written.
        const Result check = runDfrecon("check --json " + roi["output"].get<std::string>());
        ASSERT_EQ(check.exitCode, 0) << check.err;
        EXPECT_NEAR(nlohmann::json::parse(check.out)["volumeMm3"].get<double>(),
                    roi["volumeMm3"].get<double>(), 1e-3);
    }
}

// One ROI of a .slices file whose contours cross in more places than any
// reading combines: it alone is reported; the other reconstructs by name,
// and --all writes it and exits 2.
TEST(Cli, OneBrokenRoiOfASlicesFileLeavesTheOthers) {
    const fs::path file = scratch() / "one-broken.slices", dir = scratch() / "one-broken";
    std::ofstream(file) << "dfrecon-slices 1\nunits mm\n"
                           "roi good\nslice 0\ncontour 4\n0 0\n10 0\n10 10\n0 10\n"
                           "slice 2\ncontour 4\n0 0\n10 0\n10 10\n0 10\n"
                           "roi broken\nslice 0\n"
                        << dfrecon::testing::crossingCombs(300);
    const Result info = runDfrecon("info " + file.string());
    EXPECT_EQ(info.exitCode, 2);
    EXPECT_NE(info.out.find("\"good\""), std::string::npos) << info.out;
    EXPECT_NE(info.err.find(file.string() + ":17:"), std::string::npos) << info.err;
    const Result good = runDfrecon("-q reconstruct " + file.string() + " --roi good -o " +
                                   (scratch() / "good.ply").string());
    EXPECT_EQ(good.exitCode, 0) << good.err;
    const Result all = runDfrecon("-q reconstruct --all " + file.string() + " -o " + dir.string());
    EXPECT_EQ(all.exitCode, 2) << all.err;
    EXPECT_TRUE(fs::exists(dir / "good.ply"));
    EXPECT_NE(all.err.find("broken"), std::string::npos) << all.err;
}

TEST(Cli, MissingInputFileExitsTwo) {
    const Result run = runDfrecon("info /nonexistent/file.slices");
    EXPECT_EQ(run.exitCode, 2);
    EXPECT_NE(run.err.find("/nonexistent/file.slices: no such file"), std::string::npos) << run.err;
}

TEST(Cli, UsageMessagesSayWhatIsWrong) {
    const Result unknown = runDfrecon("frobnicate");
    EXPECT_EQ(unknown.exitCode, 1);
    EXPECT_NE(unknown.err.find("unknown subcommand 'frobnicate'"), std::string::npos)
        << unknown.err;
    const std::string slices = std::string(DFRECON_EXAMPLES) + "/two-rois.slices";
    const Result both = runDfrecon("reconstruct " + slices + " --all --roi PTV -o x");
    EXPECT_EQ(both.exitCode, 1);
    EXPECT_NE(both.err.find("exclude each other"), std::string::npos) << both.err;
    const Result negative =
        runDfrecon("reconstruct " + slices + " --roi PTV --pixel-mm -1 -o x.ply");
    EXPECT_EQ(negative.exitCode, 1);
    EXPECT_NE(negative.err.find("must be at least 0, not -1"), std::string::npos) << negative.err;
    EXPECT_LT(negative.err.size(), 200u) << negative.err;  // no DBL_MAX in 300 digits
}

TEST(Cli, QuietMeansQuietAlsoForMeshWriters) {
    const std::string slices = std::string(DFRECON_EXAMPLES) + "/two-rois.slices";
    for (const char* ext : {".obj", ".stl", ".off", ".ply"}) {
        const Result run = runDfrecon("-q reconstruct " + slices + " --roi PTV -o " +
                                      (scratch() / (std::string("quiet") + ext)).string());
        EXPECT_EQ(run.exitCode, 0) << run.err;
        EXPECT_EQ(run.err, "") << ext;
    }
}

TEST(Cli, UsageErrorsExitOne) {
    EXPECT_EQ(runDfrecon("").exitCode, 1);
    EXPECT_EQ(runDfrecon("frobnicate").exitCode, 1);
    EXPECT_EQ(runDfrecon("synth cube -o x.slices").exitCode, 1);
    EXPECT_EQ(runDfrecon("synth sphere").exitCode, 1);  // no -o
    EXPECT_EQ(runDfrecon("synth sphere -o x.slices --spacing -1").exitCode, 1);
    EXPECT_EQ(runDfrecon("info").exitCode, 1);
}

TEST(Cli, HelpEverywhereWithDefaultsAndUnits) {
    for (const std::string sub :
         {"", "synth ", "devices ", "info ", "fields ", "check ", "reconstruct ", "field ",
          "simplify ", "convert ", "rasterize "}) {
        const Result run = runDfrecon(sub + "--help");
        EXPECT_EQ(run.exitCode, 0) << sub;
        EXPECT_NE(run.out.find("Usage:"), std::string::npos) << sub;
    }
    const Result synth = runDfrecon("synth --help");
    EXPECT_NE(synth.out.find("--spacing FLOAT:NUMBER > 0=2"), std::string::npos) << synth.out;
    EXPECT_NE(synth.out.find("in mm"), std::string::npos);
    EXPECT_NE(synth.out.find("hollow-sphere"), std::string::npos);
}

TEST(Cli, TorusInfoShowsANestedContourOnMiddleSlices) {
    const fs::path file = scratch() / "t.slices";
    ASSERT_EQ(runDfrecon("synth torus -o " + file.string()).exitCode, 0);
    const Result run = runDfrecon("info " + file.string() + " --json");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const auto report = nlohmann::json::parse(run.out);
    const auto& roi = report["rois"][0];
    EXPECT_EQ(roi["name"], "torus");
    const auto& slices = roi["perSlice"];
    ASSERT_GE(slices.size(), 3u);
    const auto& middle = slices[slices.size() / 2]["contours"];
    ASSERT_EQ(middle.size(), 2u);
    EXPECT_EQ(middle[0]["depth"], 0);
    EXPECT_EQ(middle[1]["depth"], 1);
    EXPECT_EQ(middle[1]["role"], "hole");
    EXPECT_GT(middle[0]["areaMm2"].get<double>(), middle[1]["areaMm2"].get<double>());
}

TEST(Cli, SynthJsonReportsExactAndSlicedVolume) {
    const fs::path file = scratch() / "s.slices";
    const Result run =
        runDfrecon("synth sphere --spacing 0.5 --points 256 --json -o " + file.string());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const auto report = nlohmann::json::parse(run.out);
    const double exact = report["exactVolumeMm3"], sliced = report["planimetricVolumeMm3"];
    EXPECT_NEAR(exact, 4.0 / 3.0 * M_PI * 8000, 1e-6);
    EXPECT_NEAR(sliced / exact, 1.0, 2e-3);
}

TEST(Cli, RepairWarningsGoToStderrUnlessQuiet) {
    const fs::path file = scratch() / "repair.slices";
    std::ofstream(file) << dfrecon::testing::kHeader << "roi a\nslice 0\ncontour 5\n0 0\n10 0\n"
                        << "10 10\n0 10\n0 0\n";
    const Result loud = runDfrecon("info " + file.string());
    EXPECT_EQ(loud.exitCode, 0);
    EXPECT_NE(loud.err.find(file.string() + ":5: warning: dropped 1 repeated"), std::string::npos)
        << loud.err;
    const Result quiet = runDfrecon("--quiet info " + file.string());
    EXPECT_TRUE(quiet.err.empty()) << quiet.err;
}

TEST(Cli, FailedWriteLeavesNothingAndExitsThree) {
    const fs::path dir = scratch() / "readonly-target";
    fs::create_directories(dir);
    const Result run = runDfrecon("synth sphere -o " + (dir / "missing" / "x.slices").string());
    EXPECT_EQ(run.exitCode, 3) << run.err;
    EXPECT_NE(run.err.find("cannot write"), std::string::npos) << run.err;
    EXPECT_TRUE(fs::is_empty(dir));
}

TEST(Cli, DevicesListsPoclAndRejectsUnknownSpecs) {
    const Result run = runDfrecon("devices --json");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const auto report = nlohmann::json::parse(run.out);
    ASSERT_FALSE(report["devices"].empty());
    int selected = 0;
    for (const auto& d : report["devices"]) selected += d["selected"].get<bool>();
    EXPECT_EQ(selected, 1);
    const Result bad = runDfrecon("--device no-such-device devices");
    EXPECT_EQ(bad.exitCode, 3);
    EXPECT_NE(bad.err.find("no OpenCL device matches 'no-such-device'"), std::string::npos);
}

TEST(Cli, FieldsWritesVolumesPicturesAndLayout) {
    const fs::path out = scratch() / "fields";
    const Result run =
        runDfrecon("fields " + std::string(DFRECON_EXAMPLES) +
                   "/two-rois.slices --roi \"Left Kidney\" --png --json -o " + out.string());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const auto report = nlohmann::json::parse(run.out);
    const auto& roi = report["rois"][0];
    const std::size_t w = roi["grid"]["width"], h = roi["grid"]["height"], s = roi["slices"];
    EXPECT_EQ(s, 3u);
    EXPECT_EQ(fs::file_size(out / "Left_Kidney-distance.raw"), w * h * s * 4);
    EXPECT_EQ(fs::file_size(out / "Left_Kidney-ids.raw"), w * h * s * 4);
    EXPECT_TRUE(fs::exists(out / "Left_Kidney-distance-002.png"));
    EXPECT_TRUE(fs::exists(out / "Left_Kidney-ids-000.png"));
    EXPECT_TRUE(fs::exists(out / "Left_Kidney-medial-001.png"));   // slices 1 and 2
    EXPECT_FALSE(fs::exists(out / "Left_Kidney-medial-002.png"));  // no slice above the last
    const auto meta = nlohmann::json::parse(slurp(out / "Left_Kidney-fields.json"));
    EXPECT_EQ(meta["slices"][1]["contours"], 3);
    EXPECT_NE(slurp(out / "Left_Kidney-distance.nhdr").find("data file: Left_Kidney-distance.raw"),
              std::string::npos);
    // Several ROIs and no --roi: a usage error naming them.
    const Result ambiguous = runDfrecon("fields " + std::string(DFRECON_EXAMPLES) +
                                        "/two-rois.slices -o " + out.string());
    EXPECT_EQ(ambiguous.exitCode, 1);
    EXPECT_NE(ambiguous.err.find("Left Kidney, PTV"), std::string::npos) << ambiguous.err;
}

TEST(Cli, FieldsCanSimplifyContoursFirst) {
    const fs::path out = scratch() / "fields-simplified";
    const Result run = runDfrecon("fields " + std::string(DFRECON_EXAMPLES) +
                                  "/torus.slices --contour-error 0.5 --json -o " + out.string());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const auto s = nlohmann::json::parse(run.out)["rois"][0]["simplification"];
    EXPECT_LT(s["pointsAfter"].get<int>(), s["pointsBefore"].get<int>());
    EXPECT_LE(s["maxDeviationMm"].get<double>(), 0.5);
    EXPECT_GT(s["maxDeviationMm"].get<double>(), 0.0);
}

TEST(Cli, CheckPassesSolidsAndFailsBrokenMeshesWithExitTwo) {
    const fs::path good = scratch() / "tetra.off", open = scratch() / "open.off";
    std::ofstream(good) << "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                        << "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";
    std::ofstream(open) << "OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n";
    const Result ok = runDfrecon("check --json " + good.string());
    ASSERT_EQ(ok.exitCode, 0) << ok.err;
    const auto report = nlohmann::json::parse(ok.out);
    EXPECT_TRUE(report["validSolid"].get<bool>());
    EXPECT_EQ(report["genus"], 0);
    EXPECT_NEAR(report["volumeMm3"].get<double>(), 1.0 / 6.0, 1e-12);
    EXPECT_EQ(report["selfIntersectingPairs"], 0);
    EXPECT_TRUE(report["selfIntersectingExamples"].is_array());
    EXPECT_FALSE(report.contains("intersectingPairs"));
    const Result bad = runDfrecon("check " + open.string());
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.out.find("boundary edges 3"), std::string::npos) << bad.out;
    EXPECT_NE(bad.err.find(open.string() + ": not a watertight"), std::string::npos) << bad.err;
    EXPECT_EQ(runDfrecon("check " + (scratch() / "missing.ply").string()).exitCode, 2);
}

TEST(Cli, ReconstructWritesACheckedSolidAndReportsIt) {
    const fs::path mesh = scratch() / "torus.stl";
    const Result run = runDfrecon("-q reconstruct " + std::string(DFRECON_EXAMPLES) +
                                  "/torus.slices --json -o " + mesh.string());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const auto report = nlohmann::json::parse(run.out)["rois"][0];
    EXPECT_TRUE(report["validSolid"].get<bool>());
    EXPECT_EQ(report["genus"], 1);
    EXPECT_EQ(report["cap"], "flat");
    EXPECT_NEAR(report["volumeCc"].get<double>(), report["volumeMm3"].get<double>() / 1000, 1e-12);
    for (const char* stage : {"fields", "medialAxes", "triangulation", "check", "smooth", "write"})
        EXPECT_GE(report["seconds"][stage].get<double>(), 0.0) << stage;
    // What was written is what was reported.
    const Result check = runDfrecon("check --json " + mesh.string());
    ASSERT_EQ(check.exitCode, 0) << check.out;
    const auto checked = nlohmann::json::parse(check.out);
    EXPECT_EQ(checked["triangles"], report["triangles"]);
    // Both commands report the mesh check in one form, under the same keys
    // (check adds where the defects are; reconstruct says which slabs).
    for (const auto& [key, value] : checked.items()) {
        if (key != "command" && key != "file" && key != "defectiveTriangles" &&
            key != "defectBoxMm" && key != "selfIntersectingAt") {
            EXPECT_TRUE(report.contains(key)) << key;
        }
    }
    EXPECT_EQ(report["selfIntersectingPairs"], 0);
    EXPECT_TRUE(report["written"].get<bool>());
    EXPECT_TRUE(report["brokenSlabsMm"].empty());
    // Flat caps at half the spacing: the volume planning systems count.
    EXPECT_NEAR(report["volumeCc"].get<double>(), report["contourVolumeCc"].get<double>(),
                0.02 * report["contourVolumeCc"].get<double>());
}

TEST(Cli, CheckSaysWhereTheDefectsAre) {
    // Two tetrahedra through each other: valid apart, intersecting together.
    const fs::path crossing = scratch() / "crossing.off";
    std::ofstream(crossing) << "OFF\n8 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                            << "0.2 0.2 0.2\n1.2 0.2 0.2\n0.2 1.2 0.2\n0.2 0.2 1.2\n"
                            << "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n"
                            << "3 4 6 5\n3 4 5 7\n3 5 6 7\n3 4 7 6\n";
    const Result run = runDfrecon("check --json " + crossing.string());
    EXPECT_EQ(run.exitCode, 2);
    const auto report = nlohmann::json::parse(run.out);
    EXPECT_GT(report["selfIntersectingPairs"].get<int>(), 0);
    ASSERT_FALSE(report["selfIntersectingAt"].empty());
    const auto& first = report["selfIntersectingAt"][0];
    EXPECT_EQ(first["triangles"].size(), 2u);
    EXPECT_EQ(first["cornersMm"][0].size(), 3u);
    EXPECT_GT(report["defectiveTriangles"].get<int>(), 1);
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_GE(report["defectBoxMm"]["min"][axis].get<double>(), 0.0);
        EXPECT_LE(report["defectBoxMm"]["max"][axis].get<double>(), 1.2 + 1e-6);
    }
    const Result text = runDfrecon("check " + crossing.string());
    EXPECT_NE(text.out.find("meet: [[["), std::string::npos) << text.out;
}

TEST(Cli, ReconstructGivesValidSolidsForAHostileLabelVolume) {
    // Blobs that touch and merge, a bending tube, a shell with an island:
    // every ROI valid as written, exit 0 (4 would mean one was not).
    const dfrecon::LabelVolume volume = dfrecon::hostileLabelVolume(16);
    const fs::path nrrd = scratch() / "hostile.nrrd", dir = scratch() / "hostile";
    dfrecon::writeMaskNrrd(nrrd.string(), volume.geometry,
                           std::vector<std::uint8_t>(volume.labels.begin(), volume.labels.end()));
    const Result run =
        runDfrecon("-q reconstruct " + nrrd.string() + " --all --json -o " + dir.string());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const auto report = nlohmann::json::parse(run.out);
    ASSERT_EQ(report["rois"].size(), 3u);
    for (const auto& roi : report["rois"]) {
        EXPECT_TRUE(roi["validSolid"].get<bool>()) << roi["roi"];
        const Result check = runDfrecon("check " + roi["output"].get<std::string>());
        EXPECT_EQ(check.exitCode, 0) << check.out;
    }
    // ASCII files keep every coordinate the check saw (6 digits would not).
    for (const char* ext : {".ply", ".obj", ".off"}) {
        const fs::path ascii = scratch() / (std::string("hostile-ascii") + ext);
        const Result written = runDfrecon("-q reconstruct " + nrrd.string() +
                                          " --roi label_1 --ascii -o " + ascii.string());
        ASSERT_EQ(written.exitCode, 0) << written.err;
        const Result check = runDfrecon("check " + ascii.string());
        EXPECT_EQ(check.exitCode, 0) << ext << ": " << check.out;
    }
}

TEST(Cli, AFullDiskIsExitThreeAndLeavesNoFile) {
    // A 64 KB tmpfs in a mount namespace of the command's own (root only;
    // a file size limit cannot stand in, PoCL writes its own files).
    const fs::path mount = scratch() / "tiny";
    fs::create_directories(mount);
    if (std::system(("unshare -m sh -c 'mount -t tmpfs -o size=64k tmpfs " + mount.string() +
                     "' >/dev/null 2>&1")
                        .c_str()) != 0)
        GTEST_SKIP() << "cannot mount a tmpfs here (needs root and unshare)";
    const fs::path slices = scratch() / "full-disk.slices";
    ASSERT_EQ(runDfrecon("synth sphere --spacing 0.5 -o " + slices.string()).exitCode, 0);
    const std::string in = slices.string(), out = mount.string();
    for (const std::string& args :
         {"reconstruct " + in + " -o " + out + "/s.ply", "field " + in + " -o " + out + "/s.vdb",
          "fields " + in + " --png -o " + out + "/f",
          "rasterize " + in + " --voxel-mm 0.2 -o " + out + "/m.nrrd",
          "convert " + in + " -o " + out + "/c.dcm",
          "synth sphere --spacing 0.5 -o " + out + "/t.slices"}) {
        const fs::path err = scratch() / "full-disk.err", left = scratch() / "full-disk.left";
        const std::string script = "mount -t tmpfs -o size=64k tmpfs " + out + " && " +
                                   DFRECON_BINARY + " -q " + args + " >/dev/null 2>" +
                                   err.string() + "; code=$?; find " + out + " -type f > " +
                                   left.string() + "; exit $code";
        const int status = std::system(("unshare -m sh -c '" + script + "'").c_str());
        ASSERT_TRUE(WIFEXITED(status)) << args;
        EXPECT_EQ(WEXITSTATUS(status), 3) << args << ": " << slurp(err);
        EXPECT_NE(slurp(err).find("cannot write"), std::string::npos) << args << ": " << slurp(err);
        EXPECT_EQ(slurp(left), "") << args;
    }
}

TEST(Cli, RoisWhoseNamesClashStillGetAFileEach) {
    // "x y" and "x_y" sanitise alike, "x_y_1" is what the first would get
    // as x_y_NUMBER, "X_Y" is the same file on a case-insensitive disk, ".."
    // must not name the folder above.
    std::string text = "dfrecon-slices 1\nunits mm\n";
    for (const char* name : {"\"x y\"", "x_y", "x_y_1", "X_Y", "..", "x/y"}) {
        text += std::string("roi ") + name + "\n";
        for (double z : {0.0, 2.0})
            text += "slice " + std::to_string(z) + "\ncontour 4\n0 0\n10 0\n10 10\n0 10\n";
    }
    const fs::path input = scratch() / "clash.slices";
    std::ofstream(input) << text;
    for (const std::string command : {"reconstruct", "fields"}) {
        const fs::path dir = scratch() / ("clash-" + command);
        const Result run =
            runDfrecon("-q " + command + " " + input.string() + " --all --json -o " + dir.string());
        ASSERT_EQ(run.exitCode, 0) << command << ": " << run.err;
        const auto report = nlohmann::json::parse(run.out);
        ASSERT_EQ(report["rois"].size(), 6u) << command;
        std::set<std::string> lowerCase;
        for (const auto& entry : fs::directory_iterator(dir)) {
            std::string name = entry.path().filename().string();
            EXPECT_NE(name[0], '.') << name;
            for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
            lowerCase.insert(name);
        }
        // reconstruct: one mesh per ROI; fields: the same set of files per ROI.
        const std::size_t perRoi = command == "reconstruct" ? 1 : lowerCase.size() / 6;
        EXPECT_EQ(lowerCase.size(), 6 * perRoi) << command;
        EXPECT_GE(perRoi, 1u);
        if (command == "reconstruct") {
            std::set<std::string> outputs;
            for (const auto& roi : report["rois"]) outputs.insert(roi["output"].get<std::string>());
            EXPECT_EQ(outputs.size(), 6u);
        }
    }
}

TEST(Cli, ReconstructAllCarriesOnPastAFailingRoi) {
    // The first ROI has more contours on a plane than the fields can name;
    // the second is fine and must still be reconstructed and written.
    std::string text = "dfrecon-slices 1\nunits mm\nroi crowded\n";
    for (double z : {0.0, 2.0}) {
        text += "slice " + std::to_string(z) + "\n";
        for (int k = 0; k < 4200; ++k) {
            const double x = 3.0 * (k % 70), y = 3.0 * (k / 70);
            text += "contour 3\n" + std::to_string(x) + " " + std::to_string(y) + "\n" +
                    std::to_string(x + 1) + " " + std::to_string(y) + "\n" + std::to_string(x) +
                    " " + std::to_string(y + 1) + "\n";
        }
    }
    text += "roi fine\n";
    for (double z : {0.0, 2.0})
        text += "slice " + std::to_string(z) + "\ncontour 4\n0 0\n10 0\n10 10\n0 10\n";
    const fs::path input = scratch() / "one-fails.slices", dir = scratch() / "one-fails";
    std::ofstream(input) << text;
    const Result run =
        runDfrecon("-q reconstruct " + input.string() + " --all --json -o " + dir.string());
    EXPECT_NE(run.exitCode, 0);
    EXPECT_NE(run.exitCode, 4);
    EXPECT_NE(run.err.find("ROI 'crowded'"), std::string::npos) << run.err;
    const auto report = nlohmann::json::parse(run.out);
    ASSERT_EQ(report["rois"].size(), 2u);
    EXPECT_TRUE(report["rois"][0].contains("error"));
    EXPECT_FALSE(report["rois"][0]["written"].get<bool>());
    EXPECT_EQ(report["rois"][0]["exitCode"].get<int>(), run.exitCode);
    EXPECT_TRUE(report["rois"][1]["validSolid"].get<bool>());
    EXPECT_TRUE(fs::exists(dir / "fine.ply"));
    EXPECT_FALSE(fs::exists(dir / "crowded.ply"));
}

TEST(Cli, CompareGivesExactOverlapAndBoundedDistances) {
    const fs::path a = scratch() / "cmp-a.ply", b = scratch() / "cmp-b.ply";
    dfrecon::writeMesh(dfrecon::toTriMesh(dfrecon::boxMesh({0, 0, 0}, {10, 10, 10}, 2)),
                       a.string());
    dfrecon::writeMesh(dfrecon::toTriMesh(dfrecon::boxMesh({2, 0, 0}, {12, 10, 10}, 3)),
                       b.string());
    const Result run = runDfrecon("compare " + a.string() + " " + b.string() + " --json");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const auto report = nlohmann::json::parse(run.out);
    EXPECT_NEAR(report["dice"].get<double>(), 0.8, 1e-9);
    EXPECT_NEAR(report["jaccard"].get<double>(), 8.0 / 12, 1e-9);
    EXPECT_NEAR(report["hausdorffMm"].get<double>(), 2, report["distanceBoundMm"].get<double>());
    // A contour file's ROI is reconstructed; a surface with a hole is refused.
    const Result contours = runDfrecon("compare " + std::string(DFRECON_EXAMPLES) +
                                       "/two-rois.slices " + a.string() + " --roi-a PTV");
    EXPECT_EQ(contours.exitCode, 0) << contours.err;
    dfrecon::TriangleSoup open = dfrecon::boxMesh({0, 0, 0}, {1, 1, 1}, 1);
    open.triangles.pop_back();
    const fs::path holed = scratch() / "cmp-open.ply";
    dfrecon::writeMesh(dfrecon::toTriMesh(open), holed.string());
    const Result refused = runDfrecon("compare " + holed.string() + " " + a.string());
    EXPECT_EQ(refused.exitCode, 2);
    EXPECT_NE(refused.err.find(holed.string()), std::string::npos) << refused.err;
}

namespace {

// A .slices structure of squares of `side` at (x0, 0) on planes 0, 2, 4, 6.
std::string squareRoi(const std::string& name, double x0, double side) {
    std::string text = "roi " + name + "\n";
    for (int k = 0; k < 4; ++k) {
        text += "slice " + std::to_string(2 * k) + "\ncontour 4\n";
        text += std::to_string(x0) + " 0\n" + std::to_string(x0 + side) + " 0\n" +
                std::to_string(x0 + side) + " " + std::to_string(side) + "\n" + std::to_string(x0) +
                " " + std::to_string(side) + "\n";
    }
    return text;
}

}  // namespace

TEST(Cli, CompareStructureSetsPairsRoisByNameAndMap) {
    // Reference: PTV and Cord; test: "ptv" shifted 3 mm (matched ignoring
    // case), "Spinal Cord" (mapped) and an extra ROI. On the
    // planes the PTVs overlap 7/10 and B's contour leaves A's 1 mm band for
    // 22 mm a plane (tests/compare/test_PlaneComparison.cpp).
    const fs::path a = scratch() / "set-a.slices", b = scratch() / "set-b.slices";
    std::ofstream(a) << "dfrecon-slices 1\nunits mm\n"
                     << squareRoi("PTV", 0, 10) << squareRoi("Cord", 30, 4);
    std::ofstream(b) << "dfrecon-slices 1\nunits mm\n"
                     << squareRoi("ptv", 3, 10) << squareRoi("\"Spinal Cord\"", 30, 4)
                     << squareRoi("Extra", 60, 4);
    const fs::path csv = scratch() / "set.csv";
    // -j 1: under the sanitizers, two threads reaching CGAL's arrangement
    // at once can both report its vptr idiom before UBSan has read its
    // suppressions (tests/ubsan.supp); the pairs run one at a time here.
    const Result run =
        runDfrecon("-q compare " + a.string() + " " + b.string() +
                   " --match \"Cord=Spinal Cord\" --json -j 1 --csv " + csv.string());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const auto report = nlohmann::json::parse(run.out);
    ASSERT_EQ(report["pairs"].size(), 2u);
    const auto& ptv = report["pairs"][0];
    EXPECT_EQ(ptv["roiA"], "PTV");
    EXPECT_EQ(ptv["roiB"], "ptv");
    EXPECT_EQ(ptv["matchedBy"], "folded name");
    EXPECT_EQ(ptv["exitCode"], 0);
    EXPECT_NEAR(ptv["onPlanes"]["dice"].get<double>(), 0.7, 1e-12);
    EXPECT_NEAR(ptv["onPlanes"]["addedPathLengthMm"].get<double>(), 4 * 22, 1e-9);
    EXPECT_GT(ptv["dice"].get<double>(), 0.5);
    EXPECT_EQ(report["pairs"][1]["matchedBy"], "map");
    EXPECT_NEAR(report["pairs"][1]["dice"].get<double>(), 1, 1e-9);
    EXPECT_EQ(report["unmatchedA"].size(), 0u);
    ASSERT_EQ(report["unmatchedB"].size(), 1u);
    EXPECT_EQ(report["unmatchedB"][0], "Extra");
    std::ifstream table(csv);
    std::string header, line;
    std::getline(table, header);
    EXPECT_EQ(header.rfind("roiA,roiB,matchedBy,", 0), 0u) << header;
    int rows = 0;
    while (std::getline(table, line)) ++rows;
    EXPECT_EQ(rows, 2);
    // A map naming an ROI the set lacks is a usage error.
    EXPECT_EQ(
        runDfrecon("compare " + a.string() + " " + b.string() + " --match Cord=Nope").exitCode, 1);
}

TEST(Cli, CompareMeshWithItselfAndItsSimplification) {
    // Identical: Dice 1, every distance 0 (the shared faces take the shift).
    // Simplified within 0.5 mm: Hausdorff at most 0.5 plus the sampling.
    const fs::path torus = scratch() / "cmp-torus.ply", simple = scratch() / "cmp-torus-s.ply";
    ASSERT_EQ(runDfrecon("-q reconstruct " + std::string(DFRECON_EXAMPLES) + "/torus.slices -o " +
                         torus.string())
                  .exitCode,
              0);
    const Result self = runDfrecon("compare " + torus.string() + " " + torus.string() + " --json");
    ASSERT_EQ(self.exitCode, 0) << self.err;
    const auto same = nlohmann::json::parse(self.out);
    EXPECT_NEAR(same["dice"].get<double>(), 1, 1e-9);
    EXPECT_NEAR(same["hausdorffMm"].get<double>(), 0, 1e-9);
    EXPECT_TRUE(same["onPlanes"].is_null());
    ASSERT_EQ(runDfrecon("-q simplify " + torus.string() + " --max-error 0.5 -o " + simple.string())
                  .exitCode,
              0);
    const Result run =
        runDfrecon("compare " + torus.string() + " " + simple.string() + " --json --spacing 0.1");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const auto report = nlohmann::json::parse(run.out);
    EXPECT_LE(report["hausdorffMm"].get<double>(), 0.5 + 0.1);
    EXPECT_GT(report["dice"].get<double>(), 0.9);
}

TEST(Cli, CompareTouchingNeighboursOfAnAtlas) {
    // Brodmann areas 44 and 45 share contour edges on every plane they meet
    // (a label map's neighbours): no general position, so B is moved off A
    // (the bound says by how much that can change the intersection), and on
    // the planes the two do not overlap at all. Exit 3 before issue 36.
    const std::string atlas = "/usr/share/mricron/templates/brodmann.nii.gz";
    if (!fs::exists(atlas)) GTEST_SKIP() << atlas << " missing (make setup installs mricron-data)";
    const Result run = runDfrecon("-q compare " + atlas + " " + atlas +
                                  " --roi-a label_44 --roi-b label_45 --json");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const auto report = nlohmann::json::parse(run.out);
    EXPECT_EQ(report["overlapMethod"], "surface flux, B shifted");
    EXPECT_LT(report["intersectionBoundMm3"].get<double>(), 0.1);
    EXPECT_LT(report["dice"].get<double>(), 0.01);
    ASSERT_TRUE(report["onPlanes"]["compared"].get<bool>());
    EXPECT_EQ(report["onPlanes"]["intersectionMm3"].get<double>(), 0);
    EXPECT_GT(report["onPlanes"]["addedPathLengthMm"].get<double>(), 0);
}

TEST(Cli, InfoSummarisesByDefaultAndListsPlanesOnRequest) {
    // One line per ROI with its contour volume (100 mm² × 2 mm × 4 planes),
    // every plane only with --slices.
    const fs::path file = scratch() / "info-summary.slices";
    std::ofstream(file) << "dfrecon-slices 1\nunits mm\n"
                        << squareRoi("PTV", 0, 10) << squareRoi("Cord", 30, 4);
    const Result summary = runDfrecon("info " + file.string());
    ASSERT_EQ(summary.exitCode, 0) << summary.err;
    EXPECT_NE(summary.out.find("\"PTV\": 4 planes, 4 contours, 0.8 cc"), std::string::npos)
        << summary.out;
    EXPECT_EQ(summary.out.find("z         0: 1 contour"), std::string::npos) << summary.out;
    const Result full = runDfrecon("info --slices " + file.string());
    ASSERT_EQ(full.exitCode, 0) << full.err;
    EXPECT_NE(full.out.find("z         6: 1 contour"), std::string::npos) << full.out;
    EXPECT_GT(std::count(full.out.begin(), full.out.end(), '\n'),
              std::count(summary.out.begin(), summary.out.end(), '\n') + 6);
}

TEST(Cli, OneBadRoiInAnRtStructDoesNotBlockTheOthers) {
    // A clinical export with one ROI whose contours cross in more places
    // than any reading combines: that ROI is reported (exit 2), every other
    // one is read, chosen and reconstructed.
    dfrecon::ContourSet set;
    const std::vector<dfrecon::Polygon> square{{{0, 0}, {10, 0}, {10, 10}, {0, 10}}};
    const std::vector<dfrecon::Polygon> knot = dfrecon::testing::crossingMeanders(300);
    for (const auto& [name, contours] : {std::pair{"loop", knot}, std::pair{"good", square}}) {
        dfrecon::Roi roi;
        roi.name = name;
        for (double z : {0.0, 2.0, 4.0}) roi.slices.push_back({z, contours});
        set.rois.push_back(roi);
    }
    const fs::path dcm = scratch() / "one-bad-roi.dcm";
    dfrecon::writeRtStruct(set, dcm.string());

    const Result info = runDfrecon("info " + dcm.string());
    EXPECT_EQ(info.exitCode, 2);
    EXPECT_NE(info.err.find(dcm.string() + ": ROI 1 'loop'"), std::string::npos) << info.err;
    EXPECT_NE(info.out.find("\"good\""), std::string::npos) << info.out;

    const Result good = runDfrecon("-q reconstruct " + dcm.string() + " --roi good -o " +
                                   (scratch() / "good-only.ply").string());
    EXPECT_EQ(good.exitCode, 0) << good.err;
    const Result loop = runDfrecon("-q reconstruct " + dcm.string() + " --roi loop -o " +
                                   (scratch() / "loop.ply").string());
    EXPECT_EQ(loop.exitCode, 2) << loop.err;

    const fs::path dir = scratch() / "one-bad-roi";
    const Result all =
        runDfrecon("-q reconstruct " + dcm.string() + " --all --json -o " + dir.string());
    EXPECT_EQ(all.exitCode, 2) << all.err;
    const auto report = nlohmann::json::parse(all.out);
    ASSERT_EQ(report["rois"].size(), 2u);
    EXPECT_EQ(report["rois"][0]["exitCode"].get<int>(), 2);
    EXPECT_TRUE(report["rois"][1]["validSolid"].get<bool>());
    EXPECT_TRUE(fs::exists(dir / "good.ply"));
}

TEST(Cli, ReconstructWithSeveralJobsGivesWhatOneJobGives) {
    // Same files, same report (but for seconds), in ROI order.
    const dfrecon::LabelVolume volume = dfrecon::hostileLabelVolume(3);
    const fs::path nrrd = scratch() / "jobs.nrrd";
    dfrecon::writeMaskNrrd(nrrd.string(), volume.geometry,
                           std::vector<std::uint8_t>(volume.labels.begin(), volume.labels.end()));
    auto run = [&](const std::string& jobs) {
        const fs::path dir = scratch() / ("jobs" + jobs);
        const Result r = runDfrecon("-q reconstruct " + nrrd.string() + " --all --json -j " + jobs +
                                    " -o " + dir.string());
        EXPECT_EQ(r.exitCode, 0) << r.err;
        auto report = nlohmann::json::parse(r.out);
        report.erase("seconds");
        for (auto& roi : report["rois"]) {
            roi.erase("seconds");
            const std::string output = roi["output"].get<std::string>();
            roi["file"] = slurp(output);
            roi.erase("output");
        }
        return report;
    };
    const auto one = run("1"), three = run("3");
    ASSERT_GE(one["rois"].size(), 2u);
    EXPECT_EQ(one, three);
}

TEST(Cli, ReconstructAllWritesOneMeshPerRoi) {
    const fs::path dir = scratch() / "all-rois";
    const Result run = runDfrecon("-q reconstruct " + std::string(DFRECON_EXAMPLES) +
                                  "/two-rois.slices --all --cap dome -o " + dir.string());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_TRUE(fs::exists(dir / "Left_Kidney.ply")) << run.out;
    EXPECT_TRUE(fs::exists(dir / "PTV.ply"));
}

TEST(Cli, ReconstructRejectsBadOptionsAndLeavesNothing) {
    const std::string in = std::string(DFRECON_EXAMPLES) + "/y.slices";
    const fs::path mesh = scratch() / "never.ply";
    const Result badCap = runDfrecon("reconstruct " + in + " --cap round -o " + mesh.string());
    EXPECT_EQ(badCap.exitCode, 1);
    EXPECT_NE(badCap.err.find("flat"), std::string::npos) << badCap.err;  // the names to use
    EXPECT_EQ(runDfrecon("reconstruct " + in + " --max-depth -1 -o " + mesh.string()).exitCode, 1);
    const Result noExtension =
        runDfrecon("reconstruct " + in + " -o " + (scratch() / "mesh").string());
    EXPECT_EQ(noExtension.exitCode, 1) << noExtension.err;
    EXPECT_NE(noExtension.err.find("mesh extension"), std::string::npos) << noExtension.err;
    EXPECT_FALSE(fs::exists(mesh));
}

TEST(Cli, FieldWritesALevelSetWhoseZeroIsOnTheContours) {
    const fs::path vdb = scratch() / "torus.vdb";
    const std::string in = std::string(DFRECON_EXAMPLES) + "/torus.slices";
    const Result run = runDfrecon("-q field " + in + " --json -o " + vdb.string());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const auto report = nlohmann::json::parse(run.out);
    const double pixel = report["voxelMm"][0].get<double>();

    openvdb::initialize();
    openvdb::io::File file(vdb.string());
    file.open();
    const auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("torus"));
    file.close();
    ASSERT_TRUE(grid);
    EXPECT_EQ(grid->getGridClass(), openvdb::GRID_LEVEL_SET);
    EXPECT_EQ(grid->metaValue<std::string>("units"), "mm");
    const openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(
        *grid);
    const dfrecon::ContourSet contours = dfrecon::readSlicesFile(in).contours;
    std::size_t points = 0;
    for (const dfrecon::Slice& slice : contours.rois[0].slices)
        for (const dfrecon::Polygon& contour : slice.contours)
            for (dfrecon::Point2 p : contour) {
                // The zero crossing lies within half a voxel of every contour point.
                ASSERT_LE(std::abs(sampler.wsSample(openvdb::Vec3d(p.x, p.y, slice.zMm))),
                          0.5 * pixel)
                    << p.x << " " << p.y << " " << slice.zMm;
                ++points;
            }
    EXPECT_GT(points, 100u);

    if (std::system("command -v vdb_print >/dev/null 2>&1") == 0) {
        const fs::path listing = scratch() / "vdb_print.txt";
        ASSERT_EQ(std::system(("vdb_print -l " + vdb.string() + " >" + listing.string()).c_str()),
                  0);
        EXPECT_NE(slurp(listing).find("Name: torus"), std::string::npos) << slurp(listing);
    }
    EXPECT_EQ(runDfrecon("field " + in + " -o " + (scratch() / "torus.nrrd").string()).exitCode, 1);
}

TEST(Cli, SimplifyKeepsTheBoundAndReportsTheVerifiedDistance) {
    const std::string slices = std::string(DFRECON_EXAMPLES) + "/torus.slices";
    const fs::path full = scratch() / "torus-full.ply", small = scratch() / "torus-small.ply",
                   field = scratch() / "torus-field.vdb";
    ASSERT_EQ(runDfrecon("-q reconstruct " + slices + " -o " + full.string()).exitCode, 0);
    ASSERT_EQ(runDfrecon("-q field " + slices + " -o " + field.string()).exitCode, 0);
    const Result run =
        runDfrecon("-q simplify " + full.string() + " --max-error 0.5 --json -o " + small.string() +
                   " --contours " + slices + " --field " + field.string());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const auto report = nlohmann::json::parse(run.out);
    EXPECT_LT(report["triangles"].get<int>(), report["trianglesBefore"].get<int>() / 2);
    EXPECT_LE(report["boundMm"]["resultToInput"].get<double>(), 0.5);
    EXPECT_LE(report["boundMm"]["inputToResult"].get<double>(), 0.5);
    EXPECT_LE(report["verified"]["maxMm"].get<double>(), 0.5);
    EXPECT_LE(report["verified"]["contoursToResultMaxMm"].get<double>(), 0.5);
    EXPECT_GT(report["verified"]["fieldAbsMaxMm"].get<double>(), 0.0);
    EXPECT_TRUE(report["withinBound"].get<bool>());
    EXPECT_TRUE(report["validSolid"].get<bool>());
    EXPECT_EQ(report["genus"], 1);
    const Result check = runDfrecon("check --json " + small.string());
    ASSERT_EQ(check.exitCode, 0) << check.out;
    EXPECT_EQ(nlohmann::json::parse(check.out)["triangles"], report["triangles"]);

    // The same in one run from the contours.
    const Result once = runDfrecon("-q reconstruct " + slices + " --max-error 0.5 --json -o " +
                                   (scratch() / "torus-once.ply").string());
    ASSERT_EQ(once.exitCode, 0) << once.err;
    const auto roi = nlohmann::json::parse(once.out)["rois"][0];
    EXPECT_LE(roi["simplification"]["verified"]["contoursToResultMaxMm"].get<double>(), 0.5);
    EXPECT_EQ(roi["triangles"], roi["simplification"]["triangles"]);
    EXPECT_TRUE(roi["validSolid"].get<bool>());
}

TEST(Cli, SimplifyRefusesBadInputAndWritesNothing) {
    const fs::path open = scratch() / "open-for-simplify.off", out = scratch() / "never.ply";
    std::ofstream(open) << "OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n";
    const Result notClosed =
        runDfrecon("simplify " + open.string() + " --max-error 1 -o " + out.string());
    EXPECT_EQ(notClosed.exitCode, 2);
    EXPECT_NE(notClosed.err.find(open.string()), std::string::npos) << notClosed.err;
    EXPECT_EQ(runDfrecon("simplify " + (scratch() / "missing.ply").string() + " --max-error 1 -o " +
                         out.string())
                  .exitCode,
              2);
    const fs::path tetra = scratch() / "tetra-for-simplify.off";
    std::ofstream(tetra) << "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                         << "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";
    EXPECT_EQ(
        runDfrecon("simplify " + tetra.string() + " --max-error 0 -o " + out.string()).exitCode, 1);
    EXPECT_EQ(runDfrecon("simplify " + tetra.string() + " -o " + out.string()).exitCode, 1);
    EXPECT_EQ(runDfrecon("simplify " + tetra.string() + " --max-error 1 -o " +
                         (scratch() / "never.txt").string())
                  .exitCode,
              1);
    const Result badField = runDfrecon("simplify " + tetra.string() + " --max-error 1 --field " +
                                       open.string() + " -o " + out.string());
    EXPECT_EQ(badField.exitCode, 2);
    EXPECT_NE(badField.err.find("OpenVDB"), std::string::npos) << badField.err;
    EXPECT_FALSE(fs::exists(out));
}

// ---- DICOM RT Structure Sets and label maps --------------------------------

TEST(Cli, RtStructConvertsAndReconstructsLikeTheSlicesFile) {
    const fs::path slices = scratch() / "rt-torus.slices", dicom = scratch() / "rt-torus.dcm";
    ASSERT_EQ(runDfrecon("synth torus -o " + slices.string()).exitCode, 0);
    const Result convert = runDfrecon("convert " + slices.string() + " -o " + dicom.string());
    ASSERT_EQ(convert.exitCode, 0) << convert.err;
    const Result info = runDfrecon("info --json " + dicom.string());
    ASSERT_EQ(info.exitCode, 0) << info.err;
    const auto infoJson = nlohmann::json::parse(info.out);
    EXPECT_EQ(infoJson["format"], "DICOM RTSTRUCT");
    EXPECT_EQ(infoJson["rois"][0]["holeConvention"], "nested");
    EXPECT_EQ(infoJson["rois"][0]["number"], 1);

    auto volumeOf = [](const std::string& input, const std::string& roi) {
        const fs::path mesh = scratch() / "rt-out.ply";
        const Result run =
            runDfrecon("reconstruct --json -q " + input + " --roi " + roi + " -o " + mesh.string());
        EXPECT_EQ(run.exitCode, 0) << run.err;
        const auto report = nlohmann::json::parse(run.out)["rois"][0];
        EXPECT_TRUE(report["validSolid"].get<bool>());
        return report["volumeCc"].get<double>();
    };
    // By number, as planning systems list ROIs; DS values keep 16 characters.
    // Their last digits can tip a few of smooth mode's ring merges (each
    // decided against a 0.05 mm tolerance) one way or the other: 6e-6 of
    // the volume on this torus; without those merges the volumes agreed to
    // 1e-6, the bound this test held until then.
    const double fromSlices = volumeOf(slices.string(), "torus");
    EXPECT_NEAR(volumeOf(dicom.string(), "1"), fromSlices, 2e-5 * fromSlices);
}

TEST(Cli, BadRtStructExitsTwoNamingTheTag) {
    const fs::path notDicom = scratch() / "broken.dcm";
    std::ofstream(notDicom) << "DICM? no";
    const Result run = runDfrecon("info " + notDicom.string());
    EXPECT_EQ(run.exitCode, 2);
    EXPECT_NE(run.err.find("not a readable DICOM file"), std::string::npos) << run.err;
    EXPECT_TRUE(run.out.empty());
}

// A 20 MB structure set: minutes in a sanitized binary, so release runs only.
#ifndef DFRECON_SANITIZE_BUILD
TEST(Cli, RasterizeAllOnTheLabelVolumeGivesBackTheLabels) {
    // plastimatch's contours of every label, rasterised on the label
    // volume's own grid, taken from the CT series the labels were drawn on
    // (test_DicomImageSeries: the same grid), into one NIfTI map: the contour planes hold the
    // voxel centres, so every voxel of the labels away from the image's
    // border (4, 5, 6) agrees. ROI numbers start at 0 here, so labels are
    // positions: label_N gets N + 1. Every centre lies on a plane, where both
    // rules are the contours' inside: the field's is the quicker here
    // (test_RasterizeOnPlanes holds the solid's to the same on planes).
    const fs::path study = fs::path(DFRECON_FIXTURES) / "kmeans_axial";
    ASSERT_TRUE(fs::exists(study / "rtstruct.dcm")) << "run make setup";
    const fs::path out = scratch() / "kmeans-all.nii.gz";
    const Result run =
        runDfrecon("rasterize -q --json --all --inside field " + (study / "rtstruct.dcm").string() +
                   " --like " + (study / "dicom").string() + " -o " + out.string());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const dfrecon::LabelVolume map = dfrecon::readLabelVolume(out.string());
    const dfrecon::LabelVolume labels =
        dfrecon::readLabelVolume((study / "labels.nii.gz").string());
    ASSERT_EQ(map.labels.size(), labels.labels.size());
    const nlohmann::json report = nlohmann::json::parse(run.out);
    for (int label : {4, 5, 6}) {
        std::size_t differ = 0, inside = 0;
        for (std::size_t v = 0; v < map.labels.size(); ++v) {
            differ += (map.labels[v] == label + 1) != (labels.labels[v] == label);
            inside += labels.labels[v] == label;
        }
        EXPECT_EQ(differ, 0u) << "label " << label << ": of " << inside;
        const nlohmann::json& roi = report["rois"][label];
        EXPECT_EQ(roi["roi"], "label_" + std::to_string(label));
        EXPECT_EQ(roi["label"], label + 1);
        EXPECT_EQ(roi["insideVoxels"], inside);
    }
    // The table beside it names the labels when the map is read back.
    EXPECT_EQ(report["labelTable"], (scratch() / "kmeans-all.txt").string());
    const Result info = runDfrecon("info --json " + out.string());
    ASSERT_EQ(info.exitCode, 0) << info.err;
    // (label_1 holds none of its own: its contours enclose the others, and
    // on the contour planes, where every voxel centre lies, the smaller ROI
    // keeps each voxel.)
    const nlohmann::json read = nlohmann::json::parse(info.out);
    bool named = false;
    for (const auto& roi : read["rois"]) named = named || roi["name"] == "label_4";
    EXPECT_TRUE(named) << info.out;
}
#endif

TEST(Cli, RasterizedSphereHasTheBallsVolume) {
    const fs::path slices = scratch() / "ras-sphere.slices", out = scratch() / "ras-sphere.nrrd";
    ASSERT_EQ(runDfrecon("synth sphere -o " + slices.string()).exitCode, 0);
    const Result run =
        runDfrecon("rasterize --json -q " + slices.string() + " --voxel-mm 1 -o " + out.string());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const double ballCc = 4.0 / 3.0 * M_PI * 20 * 20 * 20 / 1000;
    EXPECT_NEAR(nlohmann::json::parse(run.out)["rois"][0]["volumeCc"].get<double>(), ballCc,
                0.02 * ballCc);
    EXPECT_EQ(runDfrecon("rasterize " + slices.string() + " -o " + out.string()).exitCode, 1);
    EXPECT_EQ(runDfrecon("rasterize " + slices.string() + " --voxel-mm 1 -o x.vdb").exitCode, 1);
}

TEST(Cli, RasterizeAllKeepsSmallerRoisAndNamesThem) {
    // A 40 mm square prism with a 10 mm one inside it, and an ROI whose
    // contours cross past any reading's limit: the map holds both good
    // ROIs, the inner one whole, and the run says the third could not be
    // read (exit 2).
    std::string text = "dfrecon-slices 1\nunits mm\n";
    const auto square = [&](double halfMm) {
        std::string slices;
        for (int z = 0; z <= 10; z += 2)
            slices += "slice " + std::to_string(z) + "\ncontour 4\n" + std::to_string(-halfMm) +
                      " " + std::to_string(-halfMm) + "\n" + std::to_string(halfMm) + " " +
                      std::to_string(-halfMm) + "\n" + std::to_string(halfMm) + " " +
                      std::to_string(halfMm) + "\n" + std::to_string(-halfMm) + " " +
                      std::to_string(halfMm) + "\n";
        return slices;
    };
    // Sides half a voxel from the centres (20.5, 5.5 mm), so no centre lies
    // on a wall.
    text += "roi Body 10 200 30\n" + square(20.5) + "roi Organ\n" + square(5.5) +
            "roi Knot\nslice 0\n" + dfrecon::testing::crossingCombs(300);
    const fs::path slices = scratch() / "nested.slices", out = scratch() / "nested.seg.nrrd";
    std::ofstream(slices) << text;
    const Result run = runDfrecon("rasterize -q --json --all " + slices.string() +
                                  " --voxel-mm 1 -o " + out.string());
    ASSERT_EQ(run.exitCode, 2) << run.err;
    EXPECT_NE(run.err.find("Knot"), std::string::npos) << run.err;
    const nlohmann::json report = nlohmann::json::parse(run.out);
    EXPECT_EQ(report["notRead"], nlohmann::json::array({"Knot"}));
    EXPECT_TRUE(report["labelTable"].is_null());  // the segmentation holds its names
    const nlohmann::json &body = report["rois"][0], &organ = report["rois"][1];
    // Each voxel is inside when its centre is inside the reconstructed solid
    // (the prisms, flat caps half a spacing beyond the end planes: 12 mm
    // tall, between layers of centres): 41 x 41 x 12 and 11 x 11 x 12
    // centres, the surfaces' volumes.
    EXPECT_EQ(report["inside"], "surface");
    EXPECT_NEAR(body["surfaceVolumeCc"].get<double>(), 41 * 41 * 12 / 1000.0, 0.002 * 20.172);
    EXPECT_EQ(body["insideVoxels"], 41 * 41 * 12);
    EXPECT_EQ(organ["insideVoxels"], 11 * 11 * 12);
    // The segmentation keeps both whole, the organ on a layer of its own.
    EXPECT_EQ(report["layers"], 2);
    EXPECT_EQ(body["layer"], 0);
    EXPECT_EQ(organ["layer"], 1);
    EXPECT_EQ(body["voxelsGivenToSmallerRois"], 0);
    EXPECT_EQ(organ["voxelsGivenToSmallerRois"], 0);
    const dfrecon::LabelVolume map = dfrecon::readLabelVolume(out.string());
    ASSERT_EQ(map.layerCount, 2);
    const std::size_t voxels = map.geometry.voxelCount();
    EXPECT_EQ(std::count(map.labels.begin(), map.labels.begin() + long(voxels), 1),
              body["insideVoxels"].get<long>());
    EXPECT_EQ(std::count(map.labels.begin() + long(voxels), map.labels.end(), 2),
              organ["insideVoxels"].get<long>());
    // Read back, each layer gives its ROIs: the body whole, hole-free.
    const dfrecon::ContourSet back = dfrecon::readLabelContours(out.string());
    ASSERT_EQ(back.rois.size(), 2u);
    EXPECT_EQ(back.rois[0].name, "Body");
    EXPECT_EQ(back.rois[1].name, "Organ");
    for (const dfrecon::Slice& slice : back.rois[0].slices) EXPECT_EQ(slice.contours.size(), 1u);

    // ROIs one after another give the same file as ROIs at once.
    const fs::path serial = scratch() / "nested-serial.seg.nrrd";
    ASSERT_EQ(runDfrecon("rasterize -q -j 1 --all " + slices.string() + " --voxel-mm 1 -o " +
                         serial.string())
                  .exitCode,
              2);
    EXPECT_EQ(slurp(serial), slurp(out));

    // A single-label map holds one label per voxel: the organ keeps its
    // voxels and the body gives them up, as the report says.
    const fs::path flat = scratch() / "nested.nrrd";
    const Result single = runDfrecon("rasterize -q --json --all " + slices.string() +
                                     " --voxel-mm 1 -o " + flat.string());
    ASSERT_EQ(single.exitCode, 2) << single.err;
    const nlohmann::json singleReport = nlohmann::json::parse(single.out);
    EXPECT_EQ(singleReport["layers"], 1);
    EXPECT_EQ(singleReport["rois"][0]["voxelsGivenToSmallerRois"],
              singleReport["rois"][1]["insideVoxels"]);
    const dfrecon::LabelVolume flatMap = dfrecon::readLabelVolume(flat.string());
    EXPECT_EQ(std::count(flatMap.labels.begin(), flatMap.labels.end(), 2),
              singleReport["rois"][1]["insideVoxels"].get<long>());

    const Result info = runDfrecon("info --json " + out.string());
    ASSERT_EQ(info.exitCode, 0) << info.err;
    const nlohmann::json named = nlohmann::json::parse(info.out);
    EXPECT_EQ(named["labelTable"], "segmentation header");
    EXPECT_EQ(named["rois"][0]["name"], "Body");
    EXPECT_EQ(named["rois"][0]["colour"], nlohmann::json::array({10, 200, 30}));
    EXPECT_EQ(named["rois"][1]["name"], "Organ");
    EXPECT_EQ(runDfrecon("rasterize --all --roi Body " + slices.string() + " --voxel-mm 1 -o " +
                         out.string())
                  .exitCode,
              1);
}

TEST(Cli, SdmWritesMapsMeshesAndAPairReport) {
    // Two closed boxes 3 mm apart and a third far away.
    const fs::path a = scratch() / "near.off", b = scratch() / "box.off", c = scratch() / "far.off";
    std::ofstream(a) << "OFF\n8 12 0\n0 0 0\n10 0 0\n10 10 0\n0 10 0\n0 0 10\n10 0 10\n10 10 10\n"
                        "0 10 10\n3 0 2 1\n3 0 3 2\n3 4 5 6\n3 4 6 7\n3 0 1 5\n3 0 5 4\n"
                        "3 1 2 6\n3 1 6 5\n3 2 3 7\n3 2 7 6\n3 3 0 4\n3 3 4 7\n";
    std::string box = slurp(a);
    auto shifted = [&](double dx) {
        std::istringstream in(box);
        std::ostringstream out;
        std::string line;
        std::getline(in, line);
        out << line << "\n";
        std::getline(in, line);
        out << line << "\n";
        for (int k = 0; k < 8; ++k) {
            double x, y, z;
            in >> x >> y >> z;
            out << x + dx << " " << y << " " << z << "\n";
        }
        in.get();
        out << in.rdbuf();
        return out.str();
    };
    std::ofstream(b) << shifted(13);
    std::ofstream(c) << shifted(100);
    const fs::path dir = scratch() / "sdm";
    const Result run = runDfrecon("sdm " + a.string() + " " + b.string() + " " + c.string() +
                                  " --size 64 --json -o " + dir.string());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const auto report = nlohmann::json::parse(run.out);
    ASSERT_EQ(report["objects"].size(), 3u);
    EXPECT_TRUE(report["objects"][0]["closed"].get<bool>());
    const auto& pair = report["pairs"][0];  // near - box
    EXPECT_EQ(pair["second"], "box");
    EXPECT_FALSE(pair["colliding"].get<bool>());
    const double gap = pair["separationMm"], bound = pair["separationBoundMm"];
    EXPECT_GE(gap, 3 - 1e-9);
    EXPECT_LE(gap, 3 + bound);
    EXPECT_NEAR(report["objects"][0]["minDistanceMm"].get<double>(), 3, bound);
    for (const char* file : {"near.ply", "near.vtk", "near_distance.tif", "near_nearest.tif",
                             "near_direction.tif", "near_distance.png", "far.ply", "report.json"})
        EXPECT_TRUE(fs::exists(dir / file)) << file;
    const std::string ply = slurp(dir / "near.ply");
    EXPECT_NE(ply.find("property float distance"), std::string::npos);
    EXPECT_NE(ply.find("property int nearest_object"), std::string::npos);
    EXPECT_NE(ply.find("property uchar red"), std::string::npos);
    const std::string vtk = slurp(dir / "near.vtk");
    EXPECT_NE(vtk.find("SCALARS distance float 1"), std::string::npos);
    // The near box's vertices facing the other box (x = 10) are 3 mm from
    // it, as VTK's own reader sees the (binary) file.
    const dfrecon::testing::VtkRead read =
        dfrecon::testing::readWithVtk({(dir / "near.vtk").string()});
    if (read.available) {
        ASSERT_TRUE(read.ok) << read.error;
        const nlohmann::json& distances = read.files[0]["pointData"]["distance"]["values"];
        EXPECT_NE(std::find(distances.begin(), distances.end(), nlohmann::json(3.0)),
                  distances.end());
    }

    // The atlas maps as OpenCV reads them: every texel with a distance has
    // a unit direction to its nearest point, stored red (x) first.
    const cv::Mat distanceMap =
        cv::imread((dir / "near_distance.tif").string(), cv::IMREAD_UNCHANGED);
    const cv::Mat directionMap =
        cv::imread((dir / "near_direction.tif").string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(distanceMap.type(), CV_32FC1);
    ASSERT_EQ(directionMap.type(), CV_32FC3);
    ASSERT_EQ(distanceMap.size(), directionMap.size());
    int texels = 0, unitDirections = 0;
    for (int row = 0; row < distanceMap.rows; ++row)
        for (int col = 0; col < distanceMap.cols; ++col) {
            if (std::isnan(distanceMap.at<float>(row, col))) continue;
            ++texels;
            const cv::Vec3f d = directionMap.at<cv::Vec3f>(row, col);
            if (std::abs(std::sqrt(d.dot(d)) - 1) < 1e-4) ++unitDirections;
        }
    EXPECT_GT(texels, 100);
    EXPECT_EQ(unitDirections, texels);

    // One mesh is a usage error; an unreadable one bad input; neither
    // leaves outputs behind.
    const fs::path none = scratch() / "sdm-none";
    EXPECT_EQ(runDfrecon("sdm " + a.string() + " -o " + none.string()).exitCode, 1);
    const fs::path broken = scratch() / "broken.off";
    std::ofstream(broken) << "OFF\n3 1 0\n0 0 0\n";
    const Result bad =
        runDfrecon("sdm " + a.string() + " " + broken.string() + " -o " + none.string());
    EXPECT_EQ(bad.exitCode, 2) << bad.err;
    EXPECT_NE(bad.err.find("broken.off"), std::string::npos) << bad.err;
    EXPECT_FALSE(fs::exists(none));
}

// A command given one ROI shows that ROI's warnings and the file's, and
// counts the others': each ROI here has a slice drawn twice (two warnings
// naming it: the planes merged, the duplicate contour dropped).
TEST(Cli, OneRoisCommandShowsItsOwnWarningsAndCountsTheOthers) {
    const fs::path file = scratch() / "two-warned.slices";
    {
        std::ofstream out(file);
        out << "dfrecon-slices 1\nunits mm\n";
        for (const char* name : {"Left", "Right"}) {
            const double x0 = std::string(name) == "Left" ? -20 : 10;
            out << "roi " << name << "\n";
            for (double z : {0.0, 2.0, 2.0, 4.0}) {
                out << "slice " << z << "\ncontour 4\n";
                out << x0 << " 0\n" << x0 + 10 << " 0\n" << x0 + 10 << " 10\n" << x0 << " 10\n";
            }
        }
    }
    const Result one = runDfrecon("reconstruct " + file.string() + " --roi Right -o " +
                                  (scratch() / "right.ply").string());
    ASSERT_EQ(one.exitCode, 0) << one.err;
    EXPECT_NE(one.err.find("ROI 'Right' has slice z=2 twice"), std::string::npos) << one.err;
    EXPECT_EQ(one.err.find("'Left'"), std::string::npos) << one.err;
    EXPECT_NE(one.err.find("2 warnings about other ROIs not shown"), std::string::npos) << one.err;
    const Result all =
        runDfrecon("reconstruct " + file.string() + " --all -o " + (scratch() / "both").string());
    ASSERT_EQ(all.exitCode, 0) << all.err;
    EXPECT_NE(all.err.find("ROI 'Left' has slice z=2 twice"), std::string::npos) << all.err;
    EXPECT_NE(all.err.find("ROI 'Right' has slice z=2 twice"), std::string::npos) << all.err;
    EXPECT_EQ(all.err.find("not shown"), std::string::npos) << all.err;
}
