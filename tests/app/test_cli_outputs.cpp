// What a command may write and the values it takes (issue 63): an output
// that is an input, another output (also ignoring case), a device, a FIFO
// or a folder is refused before any work, exit 1, naming the option, and
// the file stays as it was; NaN and infinities are no numbers; expressions
// are bounded in depth, size and summed margin.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/CliRun.hpp"
#include "tests/TempDir.hpp"

namespace fs = std::filesystem;
using dfrecon::testing::CliResult;
using dfrecon::testing::slurp;
using dfrecon::testing::TempDir;

namespace outputs_test {

const std::string kExamples = DFRECON_EXAMPLES;

CliResult runQuiet(const TempDir& dir, const std::string& args) {
    return dfrecon::testing::runCli(dir.str(), "-q " + args);
}

// Exit 1, stderr "dfrecon: OPTION PATH..." or naming `fragment`.
void expectUsage(const TempDir& dir, const std::string& args, const std::string& fragment) {
    const CliResult r = runQuiet(dir, args);
    EXPECT_EQ(r.exitCode, 1) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << args << "\n" << r.err;
}

}  // namespace outputs_test

using namespace outputs_test;

TEST(OutputGate, AnInputIsNeverReplaced) {
    const TempDir dir("outputs");
    const std::string contours = dir / "plan.slices", mesh = dir / "ptv.ply";
    fs::copy_file(kExamples + "/two-rois.slices", contours);
    const std::string before = slurp(contours);
    const std::string histogram = "histogram " + contours + " --roi 'Left Kidney' --to PTV ";
    expectUsage(dir, histogram + "-o " + contours, "it is the input " + contours);
    // Another spelling of the same file, and a hard link to it.
    expectUsage(dir, histogram + "-o " + dir.str() + "/./plan.slices", "it is the input");
    fs::create_hard_link(contours, dir / "link.slices");
    expectUsage(dir, histogram + "--plot " + (dir / "link.slices"), "it is the input");
    expectUsage(dir, "reconstruct " + contours + " --all -o " + contours, "it is the input");
    EXPECT_EQ(slurp(contours), before);
    ASSERT_EQ(runQuiet(dir, "reconstruct " + contours + " --roi PTV -o " + mesh).exitCode, 0);
    const std::string meshBefore = slurp(mesh);
    expectUsage(dir, "compare " + mesh + " " + mesh + " --csv " + mesh, "--csv " + mesh);
    expectUsage(dir, "simplify " + mesh + " --max-error 0.1 -o " + mesh, "it is the input");
    EXPECT_EQ(slurp(mesh), meshBefore);
}

TEST(OutputGate, TwoOutputsOfOneCommandNeedTwoFiles) {
    const TempDir dir("outputs");
    const std::string contours = kExamples + "/two-rois.slices";
    expectUsage(dir,
                "reconstruct " + contours + " --roi PTV -o " + (dir / "same.ply") + " --report " +
                    (dir / "same.ply"),
                "--report " + (dir / "same.ply") + ": the same file as --output");
    // One file on file systems that ignore case (macOS, Windows).
    expectUsage(dir,
                "histogram " + contours + " --roi 'Left Kidney' --to PTV -o " + (dir / "a.csv") +
                    " --plot " + (dir / "A.CSV"),
                "ignore letter case");
    EXPECT_FALSE(fs::exists(dir / "same.ply"));
    EXPECT_FALSE(fs::exists(dir / "a.csv"));
}

TEST(OutputGate, DevicesPipesAndFoldersAreNoOutputFiles) {
    const TempDir dir("outputs");
    const std::string contours = kExamples + "/two-rois.slices";
    const std::string one = "reconstruct " + contours + " --roi PTV -o ";
    expectUsage(dir, one + "/dev/null", "it is a character device");
    ASSERT_EQ(::mkfifo((dir / "pipe.ply").c_str(), 0600), 0);
    expectUsage(dir, one + (dir / "pipe.ply"), "named pipe");
    EXPECT_TRUE(fs::is_fifo(dir / "pipe.ply"));
    fs::create_directories(dir / "folder.ply");
    expectUsage(dir, one + (dir / "folder.ply"), "it is a folder");
    // A file where an output folder is asked for.
    std::ofstream(dir / "file") << "x";
    expectUsage(dir, "fields " + contours + " --roi PTV -o " + (dir / "file"), "it is a file");
    // The path stays a folder for --all, as documented.
    EXPECT_EQ(
        runQuiet(dir, "reconstruct " + contours + " --all -o " + (dir / "folder.ply")).exitCode, 0);
}

TEST(OutputGate, SdmNamesDifferInMoreThanCase) {
    const TempDir dir("outputs");
    const std::string contours = kExamples + "/two-rois.slices";
    fs::create_directories(dir / "x");
    fs::create_directories(dir / "y");
    ASSERT_EQ(
        runQuiet(dir, "reconstruct " + contours + " --roi PTV -o " + (dir / "x/lung.ply")).exitCode,
        0);
    ASSERT_EQ(
        runQuiet(dir, "reconstruct " + contours + " --roi 'Left Kidney' -o " + (dir / "y/LUNG.ply"))
            .exitCode,
        0);
    const CliResult r = runQuiet(dir, "sdm " + (dir / "x/lung.ply") + " " + (dir / "y/LUNG.ply") +
                                          " --size 32 -o " + (dir / "maps") + " --no-images");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / "maps/lung.ply"));
    EXPECT_TRUE(fs::exists(dir / "maps/LUNG_2.ply"));
}

TEST(NumberOptions, NanAndInfinityAreNoNumbers) {
    const TempDir dir("outputs");
    const std::string contours = kExamples + "/two-rois.slices";
    const std::string out = " -o " + (dir / "out.slices");
    expectUsage(dir, "margin " + contours + " --roi PTV --mm nan" + out, "--mm: 'nan' is not");
    expectUsage(dir, "margin " + contours + " --roi PTV --mm 2 --min-area nan" + out,
                "--min-area: 'nan'");
    expectUsage(dir, "histogram " + contours + " --roi 'Left Kidney' --to PTV --bin inf",
                "--bin: 'inf'");
    expectUsage(dir, "reconstruct " + contours + " --roi PTV --pixel-mm -inf -o " + (dir / "x.ply"),
                "--pixel-mm");
    EXPECT_FALSE(fs::exists(dir / "out.slices"));
    // A job count beyond the cores is the cores, not a crash.
    const CliResult many = runQuiet(dir, "compare " + contours + " " + contours + " -j 4294967295");
    EXPECT_EQ(many.exitCode, 0) << many.err;
}

TEST(RoiExpressions, DepthSizeAndMarginsAreBounded) {
    const TempDir dir("outputs");
    const std::string contours = kExamples + "/two-rois.slices";
    const std::string out = " -o " + (dir / "out.slices");
    const std::string deep = "X = " + std::string(60000, '(') + "PTV" + std::string(60000, ')');
    std::ofstream(dir / "deep.txt") << deep;
    expectUsage(dir, "combine " + contours + " --expr \"$(cat " + (dir / "deep.txt") + ")\"" + out,
                "nested deeper than 100");
    std::string wide = "X = PTV";
    for (int k = 0; k < 10000; ++k) wide += " | PTV";
    std::ofstream(dir / "wide.txt") << wide;
    expectUsage(dir, "combine " + contours + " --expr \"$(cat " + (dir / "wide.txt") + ")\"" + out,
                "more than 1000");
    expectUsage(dir, "combine " + contours + " --expr 'X = PTV + 150 + 150'" + out,
                "add up to 300 mm");
    expectUsage(dir, "combine " + contours + " --expr \"$(printf 'X\\001Y = PTV + 1')\"" + out,
                "--expr: the new ROI's name holds a control character");
    expectUsage(dir,
                "margin " + contours + " --roi PTV --mm 2 --name \"$(printf 'bad\\tname')\"" + out,
                "--name: the new ROI's name holds a control character");
    EXPECT_FALSE(fs::exists(dir / "out.slices"));
}
