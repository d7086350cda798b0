// "-" for standard input and output (app/StandardStreams.hpp, docs/cli.md
// "Standard input and output"), as a user pipes dfrecon: .slices in, one
// mesh or .slices file out, the same results as with files, the same input
// limits, and "-" refused where a format cannot stream.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "geometry/MeshCheck.hpp"
#include "geometry/TriangleSoup.hpp"
#include "io/mesh/MeshIO.hpp"
#include "tests/CliRun.hpp"
#include "tests/TempDir.hpp"

namespace fs = std::filesystem;
using dfrecon::testing::TempDir;

namespace {

using Result = dfrecon::testing::CliResult;

using dfrecon::testing::slurp;

// Runs a shell pipeline in which DFRECON stands for the program; the
// pipeline's stdout and stderr are kept, its exit code is the last command's.
Result runPipeline(const TempDir& dir, std::string pipeline) {
    for (std::size_t at; (at = pipeline.find("DFRECON")) != std::string::npos;)
        pipeline.replace(at, 7, std::string(DFRECON_BINARY) + " -q");
    return dfrecon::testing::runShell(dir.str(), pipeline);
}

const std::string kTorus = std::string(DFRECON_EXAMPLES) + "/torus.slices";
const std::string kTwoRois = std::string(DFRECON_EXAMPLES) + "/two-rois.slices";

}  // namespace

TEST(CliStreams, InfoReadsSlicesFromStandardInputAsFromTheFile) {
    const TempDir dir("cli-streams");
    const Result fromFile = runPipeline(dir, "DFRECON info --json " + kTwoRois);
    const Result fromPipe = runPipeline(dir, "cat " + kTwoRois + " | DFRECON info --json -");
    ASSERT_EQ(fromFile.exitCode, 0) << fromFile.err;
    ASSERT_EQ(fromPipe.exitCode, 0) << fromPipe.err;
    nlohmann::json file = nlohmann::json::parse(fromFile.out);
    nlohmann::json pipe = nlohmann::json::parse(fromPipe.out);
    EXPECT_EQ(pipe["file"], "-");
    EXPECT_EQ(pipe["rois"], file["rois"]);
    EXPECT_EQ(pipe["format"], "dfrecon-slices 1");
}

TEST(CliStreams, MeshOnStandardOutputIsTheFileWithoutTheReport) {
    const TempDir dir("cli-streams");
    const Result toFile =
        runPipeline(dir, "DFRECON reconstruct " + kTorus + " -o " + (dir / "torus.stl"));
    ASSERT_EQ(toFile.exitCode, 0) << toFile.err;
    for (const std::string format : {"stl", "ply", "obj", "off"}) {
        const Result toPipe = runPipeline(
            dir, "DFRECON reconstruct " + kTorus + " -o - --format " + format + " --ascii");
        ASSERT_EQ(toPipe.exitCode, 0) << format << ": " << toPipe.err;
        const std::string piped = dir / ("piped." + format);
        std::ofstream(piped, std::ios::binary) << toPipe.out;
        // The report went to stderr, and what came out is a whole mesh.
        EXPECT_NE(toPipe.err.find("-> standard output"), std::string::npos) << toPipe.err;
        const dfrecon::MeshCheckReport check = dfrecon::checkMesh(dfrecon::readTriangleSoup(piped));
        EXPECT_TRUE(check.validSolid()) << format;
    }
    // Binary STL: the very bytes of the file.
    const Result binary = runPipeline(dir, "DFRECON reconstruct " + kTorus + " -o - --format stl");
    ASSERT_EQ(binary.exitCode, 0) << binary.err;
    EXPECT_EQ(binary.out, slurp(dir / "torus.stl"));
}

TEST(CliStreams, SynthPipesIntoReconstruct) {
    const TempDir dir("cli-streams");
    const std::string mesh = dir / "sphere.ply";
    const Result run = runPipeline(
        dir, "DFRECON synth sphere -o - | DFRECON reconstruct - -o " + mesh + " --json");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const nlohmann::json report = nlohmann::json::parse(run.out);
    EXPECT_EQ(report["input"], "-");
    EXPECT_TRUE(report["rois"][0]["validSolid"].get<bool>());
    // synth's own report went to stderr, not into the pipe.
    EXPECT_NE(run.err.find("wrote standard output"), std::string::npos) << run.err;
    const double volume = dfrecon::checkMesh(dfrecon::readTriangleSoup(mesh)).volumeMm3;
    const double sphere = 4.0 / 3.0 * M_PI * 20 * 20 * 20;
    EXPECT_NEAR(volume, sphere, 0.02 * sphere);
}

TEST(CliStreams, StandardInputIsHeldToTheInputLimits) {
    const TempDir dir("cli-streams");
    // An endless line: refused once it passes the line limit, as from a file,
    // never read to the end (the pipe has none).
    const Result endless =
        runPipeline(dir, "yes x | tr -d '\\n' | timeout 60 " + std::string("DFRECON info -"));
    EXPECT_EQ(endless.exitCode, 2) << endless.err;
    EXPECT_NE(endless.err.find("<stdin>:1:"), std::string::npos) << endless.err;
    // What is not .slices is bad input naming standard input.
    const Result dicom = runPipeline(dir, "printf 'DICM' | DFRECON info -");
    EXPECT_EQ(dicom.exitCode, 2) << dicom.err;
    EXPECT_NE(dicom.err.find("<stdin>"), std::string::npos) << dicom.err;
}

TEST(CliStreams, DashIsRefusedWhereTheFormatCannotStream) {
    const TempDir dir("cli-streams");
    const std::string mesh = dir / "torus.ply";
    ASSERT_EQ(runPipeline(dir, "DFRECON reconstruct " + kTorus + " -o " + mesh).exitCode, 0);
    const std::string refused[] = {
        "DFRECON reconstruct " + kTorus + " -o -",                       // no --format
        "DFRECON reconstruct " + kTorus + " -o - --format ply --json",   // two on stdout
        "DFRECON reconstruct " + kTwoRois + " --all -o - --format ply",  // several meshes
        "DFRECON reconstruct " + kTorus + " -o " + (dir / "x.ply") + " --format stl",
        "cat " + mesh + " | DFRECON simplify - -o " + (dir / "s.ply") + " --max-error 0.1",
        "cat " + mesh + " | DFRECON check -",
        "DFRECON field " + kTorus + " -o -",
        "DFRECON fields " + kTorus + " -o -",
        "DFRECON convert " + kTorus + " -o -",
        "DFRECON rasterize " + kTorus + " -o -",
        "DFRECON segment " + mesh + " -o -",
        "DFRECON sdm " + mesh + " - -o " + (dir / "sdm"),
        "DFRECON synth sphere -o - --json",
    };
    for (const std::string& pipeline : refused) {
        const Result run = runPipeline(dir, "cd " + dir.str() + " && " + pipeline);
        EXPECT_EQ(run.exitCode, 1) << pipeline << "\n" << run.err;
        EXPECT_FALSE(run.err.empty()) << pipeline;
        EXPECT_TRUE(run.out.empty()) << pipeline;
        EXPECT_FALSE(fs::exists(dir / "-")) << pipeline << " made a file named '-'";
    }
}
