// Hostile inputs (issue 16) as a user meets them: every one ends quickly,
// under a 3 GB address-space cap, with exit 2 and a message that starts
// with the file's name. The small ones live in tests/data/hostile with
// their expectations in cases.tsv; the large ones are generated here.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/CliRun.hpp"
#include "tests/HostileDicom.hpp"
#include "tests/SyntheticDicomSeries.hpp"
#include "tests/TempDir.hpp"

namespace fs = std::filesystem;
using dfrecon::testing::TempDir;

namespace {

using Result = dfrecon::testing::CliResult;
using dfrecon::testing::slurp;

// The address-space cap the issue sets, as a shell prefix (none under
// AddressSanitizer, whose shadow memory needs far more).
std::string memoryCap() {
#ifdef DFRECON_SANITIZE_BUILD
    return "";
#else
    return "ulimit -v 3000000; ";
#endif
}

// Runs dfrecon -q with `args` under the cap.
Result runCapped(const TempDir& dir, const std::string& args) {
    return dfrecon::testing::runCli(dir.str(), "-q " + args, memoryCap());
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    for (std::size_t at = text.find(from); at != std::string::npos;
         at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
    return text;
}

// Exit 2 (or `exitCode`), stderr "dfrecon: FILE..." saying `fragment`. A
// hang is caught by the tests' ctest timeout (tests/CMakeLists.txt), not by
// timing the run: wall-clock limits fail on a loaded machine.
void expectRefused(const TempDir& dir, const std::string& file, const std::string& args,
                   const std::string& fragment, int exitCode = 2) {
    const Result r = runCapped(dir, args);
    EXPECT_EQ(r.exitCode, exitCode) << args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("dfrecon: " + file, 0), 0u) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << args << "\n" << r.err;
}

// One line of cases.tsv.
struct Case {
    std::string file, fragment, args, name;
    int exitCode = 0;
};

// How ctest names a case's parameter: its line of cases.tsv.
void PrintTo(const Case& c, std::ostream* out) {
    *out << c.file << ": " << c.args;
}

std::vector<Case> corpusCases() {
    std::vector<Case> cases;
    std::ifstream in(std::string(DFRECON_TEST_DATA) + "/hostile/cases.tsv");
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream fields(line);
        Case c;
        std::string exitCode;
        std::getline(fields, c.file, '\t');
        std::getline(fields, exitCode, '\t');
        std::getline(fields, c.fragment, '\t');
        std::getline(fields, c.args);
        c.exitCode = std::atoi(exitCode.c_str());
        // A test name: the file's letters and digits, and the line.
        for (char ch : c.file) c.name += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
        c.name += "_line" + std::to_string(number);
        cases.push_back(c);
    }
    return cases;
}

}  // namespace

class HostileCorpus : public ::testing::TestWithParam<Case> {};

TEST_P(HostileCorpus, EndsWithItsExitCodeNamingTheFile) {
    const Case& c = GetParam();
    const TempDir dir("hostile-" + c.name);
    const std::string corpus = std::string(DFRECON_TEST_DATA) + "/hostile/";
    ASSERT_TRUE(fs::exists(corpus + c.file)) << c.file;
    std::string args = replaced(c.args, "{in}", corpus + c.file);
    args = replaced(replaced(args, "{out}", dir / "out"), "{examples}", DFRECON_EXAMPLES);
    expectRefused(dir, corpus + c.file, args, c.fragment, c.exitCode);
}

INSTANTIATE_TEST_SUITE_P(CasesTsv, HostileCorpus, ::testing::ValuesIn(corpusCases()),
                         [](const auto& testInfo) { return testInfo.param.name; });

TEST(HostileInputs, CorpusCoversEveryReader) {
    int mesh = 0, label = 0, manifest = 0, contours = 0;
    for (const Case& c : corpusCases()) {
        mesh += c.file.rfind("mesh-", 0) == 0;
        label += c.file.rfind("label-", 0) == 0;
        manifest += c.file.rfind("manifest-", 0) == 0;
        contours += c.file.rfind("rtstruct-", 0) == 0 || c.file.rfind("slices-", 0) == 0;
    }
    EXPECT_GE(mesh, 10);
    EXPECT_GE(label, 10);
    EXPECT_GE(manifest, 2);
    EXPECT_GE(contours, 2);
}

TEST(HostileInputs, SimplifyRefusesWhatCheckRefusesBeforeDecimating) {
    // Two 1000-gons back to back: closed and manifold, but folded onto
    // itself; the decimation ran for minutes.
    const TempDir dir("hostile-simplify");
    const std::string path = dir / "pillow.off";
    std::ofstream off(path);
    const int n = 1000;
    off << "OFF\n" << n << " 2 0\n";
    for (int k = 0; k < n; ++k)
        off << 10 * std::cos(2 * M_PI * k / n) << ' ' << 10 * std::sin(2 * M_PI * k / n) << " 0\n";
    off << n;
    for (int k = 0; k < n; ++k) off << ' ' << k;
    off << '\n' << n;
    for (int k = n - 1; k >= 0; --k) off << ' ' << k;
    off << '\n';
    off.close();
    expectRefused(dir, path, "simplify " + path + " --max-error 0.1 -o " + dir / "out.ply",
                  "not a valid closed solid");
    EXPECT_FALSE(fs::exists(dir / "out.ply"));
}

TEST(HostileInputs, DeeplyNestedDicomIsRefusedNotACrash) {
    // 100 000 nested sequences in a private tag: DCMTK's parser exhausted
    // the stack (SIGSEGV).
    const TempDir dir("hostile-nesting");
    const std::string path = dir / "nested.dcm";
    std::ofstream(path, std::ios::binary) << dfrecon::testing::nestedSequencesDicom(100000);
    expectRefused(dir, path, "info " + path, "sequences nested more than 64 deep");
    expectRefused(dir, path, "reconstruct " + path + " --all -o " + dir / "out",
                  "sequences nested more than 64 deep");
    // As the reference of convert --like too.
    expectRefused(dir, path,
                  "convert " + std::string(DFRECON_EXAMPLES) + "/torus.slices --like " + path +
                      " -o " + dir / "out.dcm",
                  "sequences nested more than 64 deep");
}

TEST(HostileInputs, MutuallyCrossingXorContoursAreRefusedNotACrash) {
    // 150 stars crossing one another on one plane: 2.5 GB in CGAL, then
    // SIGSEGV.
    const TempDir dir("hostile-xor");
    const std::string path = dir / "stars.dcm";
    std::ofstream(path, std::ios::binary) << dfrecon::testing::crossingStarsRtStruct(150, 64, 1);
    expectRefused(dir, path, "info " + path,
                  "ROI 1 'stars', plane 0 mm: 150 contours meeting in more than 49850 places");
}

TEST(HostileInputs, ContourOverTheFieldIdLimitIsBadInputNotUsage) {
    // A valid contour of more points than the distance fields index
    // (2^19 - 1) was a usage error (exit 1) without the file.
    const TempDir dir("hostile-points");
    const std::string path = dir / "long.slices";
    {
        std::ofstream out(path);
        const int n = 1 << 19;
        out << "dfrecon-slices 1\nunits mm\nroi long\nslice 0\ncontour " << n << "\n";
        char line[64];
        for (int k = 0; k < n; ++k) {
            std::snprintf(line, sizeof line, "%.5f %.5f\n", 50 * std::cos(2 * M_PI * k / n),
                          50 * std::sin(2 * M_PI * k / n));
            out << line;
        }
    }
    expectRefused(dir, path, "reconstruct " + path + " -o " + dir / "out.ply",
                  "has over 524287 points, the most the distance fields can index");
}

TEST(HostileInputs, OutOfMemoryNamesTheFile) {
#ifdef DFRECON_SANITIZE_BUILD
    GTEST_SKIP() << "AddressSanitizer needs more address space than the cap leaves";
#else
    // A valid volume within the budget (2.5·10^8 voxels, 1.25 GB with their
    // labels) read under a 1 GB address-space cap: memory runs out.
    const TempDir dir("hostile-memory");
    const std::string path = dir / "large.nrrd";
    const std::string header =
        "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 1000 1000 250\nencoding: raw\n\n";
    std::ofstream(path, std::ios::binary) << header;
    fs::resize_file(path, header.size() + 250000000u);  // sparse: zeros, no disk
    const std::string err = dir / "stderr.txt";
    const int status = std::system(("ulimit -v 1000000; exec " + std::string(DFRECON_BINARY) +
                                    " -q info " + path + " >/dev/null 2>" + err)
                                       .c_str());
    EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 3);
    EXPECT_EQ(slurp(err), "dfrecon: " + path + ": out of memory while reading it\n");
#endif
}

// ---- The second sweep (issue 35): batch records and manifests, label
// tables, text encodings, pipes and standard streams, option extremes. ----

namespace {

std::string writeFile(const TempDir& dir, const std::string& name, const std::string& bytes) {
    const std::string path = dir / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

// A batch output folder with one done entry "a" of the torus: its record
// and mesh, for tests that then spoil the record.
std::string batchOutput(const TempDir& dir) {
    const std::string manifest = writeFile(
        dir, "manifest.csv", "input,id\n" + std::string(DFRECON_EXAMPLES) + "/torus.slices,a\n");
    const Result r = runCapped(dir, "batch " + manifest + " -o " + dir / "out");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return dir / "out";
}

std::string volumeOfTheTorus(const TempDir& dir) {
    const std::string volume = dir / "torus.nrrd";
    const Result r = runCapped(dir, "rasterize " + std::string(DFRECON_EXAMPLES) +
                                        "/torus.slices --voxel-mm 2 -o " + volume);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    fs::remove(dir / "torus.txt");  // the table rasterize wrote: each test brings its own
    return volume;
}

}  // namespace

TEST(HostileInputs, BoundsBelowCoordinateResolutionAreUsageErrorsNotCrashes) {
    // 1e-16 mm recursed without end in the coverage of a collapse (SIGSEGV);
    // 1e-12..1e-4 mm ran out of memory sampling the contours every bound/8.
    const TempDir dir("hostile-max-error");
    const std::string y = std::string(DFRECON_EXAMPLES) + "/y.slices";
    for (const char* command : {"reconstruct", "simplify"}) {
        const std::string input = std::string(command) == "simplify" ? dir / "y.ply" : y;
        if (input != y) {
            ASSERT_EQ(runCapped(dir, "reconstruct " + y + " -o " + input).exitCode, 0);
        }
        const Result r = runCapped(
            dir, std::string(command) + " " + input + " --max-error 1e-16 -o " + dir / "out.ply");
        EXPECT_EQ(r.exitCode, 1) << r.err;
        EXPECT_NE(r.err.find("--max-error: must be"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("at least 1e-06 mm, not 1e-16"), std::string::npos) << r.err;
    }
    // At the floor it works, within the memory cap.
    const Result r =
        runCapped(dir, "reconstruct " + y + " --max-error 1e-6 --json -o " + dir / "out.ply");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("\"withinBound\": true"), std::string::npos) << r.out;
}

TEST(HostileInputs, ABatchEntryWhoseProcessDiesFailsAlone) {
    // A crash in one entry killed the whole batch, on every rerun. Crashes
    // are no longer known, so the worker is told to raise SIGSEGV on entry b.
    const TempDir dir("hostile-batch-crash");
    const std::string torus = std::string(DFRECON_EXAMPLES) + "/torus.slices";
    const std::string manifest =
        writeFile(dir, "m.csv", "input,id\n" + torus + ",a\n" + torus + ",b\n" + torus + ",c\n");
    const std::string out = dir / "out";
    const std::string batch = std::string(DFRECON_BINARY) + " -q batch " + manifest + " -o " + out;
    for (const char* jobs : {" -j 1", " -j 2"}) {
        fs::remove_all(out);
        const Result r = dfrecon::testing::runShell(
            dir.str(), "DFRECON_BATCH_WORKER_CRASH_ENTRY=b exec " + batch + jobs + " </dev/null");
        EXPECT_EQ(r.exitCode, 3) << r.err;
        EXPECT_NE(r.out.find("a: 1 ROI done"), std::string::npos) << r.out;
        EXPECT_NE(r.out.find("b: failed: the entry's process ended on signal 11"),
                  std::string::npos)
            << r.out;
        EXPECT_NE(r.out.find("c: 1 ROI done"), std::string::npos) << r.out;
        EXPECT_TRUE(fs::exists(out + "/c/torus.ply"));
        // The crashed entry has a record, so the report shows it.
        const Result report = runCapped(dir, "batch-report " + out + " -o -");
        EXPECT_EQ(report.exitCode, 0) << report.err;
        EXPECT_NE(report.out.find("\nb,,,,,,,0,3,the entry's process ended on signal 11"),
                  std::string::npos)
            << report.out;
    }
    // A rerun skips it (same input, options, version), and skips the others.
    const Result rerun = runCapped(dir, "batch " + manifest + " -o " + out);
    EXPECT_EQ(rerun.exitCode, 3) << rerun.err;
    EXPECT_NE(rerun.out.find("0 done, 3 skipped"), std::string::npos) << rerun.out;
}

TEST(HostileInputs, SpoiledBatchRecordsAreBadInputNotHangsOrCrashes) {
    const TempDir dir("hostile-records");
    const std::string out = batchOutput(dir);
    const std::string record = out + "/a/record.json";
    // Nested 100 000 deep: batch-report crashed.
    writeFile(dir, "out/a/record.json",
              "{\"format\": \"dfrecon-batch-record 1\", \"id\": \"a\", \"entry\": 1, \"error\": " +
                  std::string(100000, '[') + std::string(100000, ']') + "}");
    expectRefused(dir, record, "batch-report " + out, "lists or objects nested more than 16 deep");
    // A named pipe: batch-report and the rerun hung on opening it.
    fs::remove(record);
    ASSERT_EQ(std::system(("mkfifo " + record).c_str()), 0);
    expectRefused(dir, record, "batch-report " + out, "a named pipe, not a regular file");
    Result r = runCapped(dir, "batch " + dir / "manifest.csv" + " -o " + out);
    EXPECT_EQ(r.exitCode, 0) << r.err;  // the entry ran again and replaced it
    EXPECT_NE(r.out.find("a: 1 ROI done"), std::string::npos) << r.out;
    // A link to /dev/zero: 2 GB read before refusing.
    fs::remove(record);
    fs::create_symlink("/dev/zero", record);
    expectRefused(dir, record, "batch-report " + out, "a character device, not a regular file");
    // A mesh outside the entry's folder: trusted on resume.
    fs::remove(record);
    r = runCapped(dir, "batch " + dir / "manifest.csv" + " -o " + out);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::string text = slurp(record);
    const std::string mesh = "\"mesh\": \"torus.ply\"";
    ASSERT_NE(text.find(mesh), std::string::npos) << text;
    text.replace(text.find(mesh), mesh.size(), "\"mesh\": \"../../manifest.csv\"");
    writeFile(dir, "out/a/record.json", text);
    expectRefused(dir, record, "batch-report " + out,
                  "/rois/0/mesh is not the name of a file in the entry's folder");
    r = runCapped(dir, "batch " + dir / "manifest.csv" + " -o " + out);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("a: 1 ROI done"), std::string::npos) << r.out;  // not "skipped"
}

TEST(HostileInputs, BatchReportToStandardOutputWritesNoFile) {
    const TempDir dir("hostile-report-stdout");
    const std::string out = batchOutput(dir);
    const Result r = runCapped(dir, "batch-report " + out + " -o -");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out.rfind("entry,roi,mesh,", 0), 0u) << r.out;
    EXPECT_NE(r.out.find("\na,torus,a/torus.ply,"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(dir / "-.csv"));
    EXPECT_FALSE(fs::exists(dir / "-.json"));
}

TEST(HostileInputs, ManifestsThatAreNoManifestsAreRefusedInTime) {
    const TempDir dir("hostile-manifests");
    const std::string torus = std::string(DFRECON_EXAMPLES) + "/torus.slices";
    // A repeated key: the last one silently won.
    const std::string repeated = writeFile(
        dir, "repeated.json", "[{\"input\": \"" + torus + "\", \"input\": \"other.slices\"}]");
    expectRefused(dir, repeated, "batch " + repeated + " -o " + dir / "out",
                  "the key 'input' a second time in one object, at /0/input");
    // A pipe and a device instead of a manifest.
    const std::string pipe = dir / "pipe.csv";
    ASSERT_EQ(std::system(("mkfifo " + pipe).c_str()), 0);
    expectRefused(dir, pipe, "batch " + pipe + " -o " + dir / "out",
                  "a named pipe, not a regular file");
    // An input of 100 GB (sparse) was hashed in full before being read.
    const std::string giant = dir / "giant.slices";
    std::ofstream(giant).close();
    fs::resize_file(giant, std::uint64_t(100) << 30);
    const std::string manifest = writeFile(dir, "giant.csv", "input,id\n" + giant + ",g\n");
    const Result r = runCapped(dir, "batch " + manifest + " -o " + dir / "out");
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("dfrecon: entry g (" + manifest + ":2): " + giant +
                         ": larger than 4096 MiB, the limit of an input file"),
              std::string::npos)
        << r.err;
    // 200 000 entries: the JSON parse was quadratic (minutes), now as fast
    // as the CSV one; one shard of one entry runs.
    std::string list = "[";
    for (int k = 0; k < 200000; ++k)
        list += std::string(k ? "," : "") + "{\"input\": \"" + torus + "\", \"id\": \"e" +
                std::to_string(k) + "\"}\n";
    const std::string big = writeFile(dir, "big.json", list + "]");
    const Result many = runCapped(dir, "batch " + big + " -o " + dir / "many --shard 0/200000");
    EXPECT_EQ(many.exitCode, 0) << many.err;
    EXPECT_NE(many.out.find("e0: 1 ROI done"), std::string::npos) << many.out;
}

TEST(HostileInputs, TextThatIsNotUtf8IsReadAsWindows1252) {
    // Latin-1 names are common in clinics: exit 3 with a raw JSON-library
    // message, and in batch a mesh without a record.
    const TempDir dir("hostile-latin1");
    std::string slices = slurp(std::string(DFRECON_EXAMPLES) + "/torus.slices");
    slices.replace(slices.find("roi torus"), 9, "roi L\xE4sion");
    const std::string path = writeFile(dir, "caf\xE9.slices", slices);
    Result r = runCapped(dir, "info " + path + " --json");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("\"name\": \"L\xC3\xA4sion\""), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("caf\xEF\xBF\xBD.slices"), std::string::npos) << r.out;  // U+FFFD
    // In a batch: the entry's record is written, and the report lists it.
    const std::string manifest = writeFile(dir, "m.csv", "input,id\n" + path + ",a\n");
    r = runCapped(dir, "batch " + manifest + " -o " + dir / "out");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    r = runCapped(dir, "batch-report " + dir / "out" + " -o -");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("\na,L\xC3\xA4sion,a/L__sion.ply,"), std::string::npos) << r.out;
    // A label table: its names too.
    const std::string volume = volumeOfTheTorus(dir);
    const std::string table = writeFile(dir, "names.txt", "1 C\xF4t\xE9_D\n");
    r = runCapped(dir, "--label-table " + table + " info " + volume + " --json");
    EXPECT_EQ(r.exitCode, 0) << r.err;  // and the usage line's order works
    EXPECT_NE(r.out.find("\"name\": \"C\xC3\xB4t\xC3\xA9_D\""), std::string::npos) << r.out;
}

TEST(HostileInputs, LabelTablesThatLieAreRefusedByLine) {
    const TempDir dir("hostile-label-table");
    const std::string volume = volumeOfTheTorus(dir);
    // A colour of 1e9 or nan was dropped silently; a control character was
    // exit 3.
    const std::pair<const char*, const char*> cases[] = {
        {"1 torus 1e9 0 0\n", "red '1e9' is not in 0..255"},
        {"1 torus 0 nan 0 255\n", "green 'nan' is not in 0..255"},
        {"# a comment\n1 tor\x1bus\n", "a control character (0x1B) in the name"},
    };
    for (const auto& [text, problem] : cases) {
        const std::string table = writeFile(dir, "table.txt", text);
        expectRefused(dir, table, "--label-table " + table + " info " + volume, problem);
    }
    expectRefused(dir, dir / "table.txt", "--label-table " + dir / "table.txt" + " info " + volume,
                  ":2: a control character");
}

TEST(HostileInputs, NamesThatWritersWriteReadersReadBack) {
    const TempDir dir("hostile-names");
    std::string slices = slurp(std::string(DFRECON_EXAMPLES) + "/torus.slices");
    // 300 bytes went into a label table and .seg.nrrd that info refused.
    std::string longName = slices;
    longName.replace(longName.find("roi torus"), 9, "roi " + std::string(300, 'x'));
    const std::string tooLong = writeFile(dir, "long.slices", longName);
    expectRefused(dir, tooLong,
                  "rasterize " + tooLong + " --all --voxel-mm 2 -o " + dir / "l.seg.nrrd",
                  ":3: an ROI name of 300 bytes, over the 256 a name may have");
    // GTV "left" (valid DICOM) was a usage error when converted to .slices.
    std::string quoted = slices;
    quoted.replace(quoted.find("roi torus"), 9, "roi \"GTV \"\"left\"\"\"");
    const std::string source = writeFile(dir, "quoted.slices", quoted);
    ASSERT_EQ(runCapped(dir, "convert " + source + " -o " + dir / "q.dcm").exitCode, 0);
    Result r = runCapped(dir, "convert " + dir / "q.dcm" + " -o " + dir / "back.slices");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(slurp(dir / "back.slices").find("roi \"GTV \"\"left\"\"\""), std::string::npos);
    r = runCapped(dir, "info " + dir / "back.slices" + " --json");
    EXPECT_NE(r.out.find("\"name\": \"GTV \\\"left\\\"\""), std::string::npos) << r.out;
}

TEST(HostileInputs, PipesAndFullOutputsEndWithTheirErrors) {
    const TempDir dir("hostile-streams");
    const std::string torus = std::string(DFRECON_EXAMPLES) + "/torus.slices";
    // A report to a full standard output was exit 0.
    Result r = dfrecon::testing::runShell(
        dir.str(), "exec " + std::string(DFRECON_BINARY) + " info " + torus + " --json >/dev/full");
    EXPECT_EQ(r.exitCode, 3) << r.err;
    EXPECT_EQ(r.err, "dfrecon: cannot write to standard output: No space left on device\n");
    // A .slices that is a pipe hung.
    const std::string pipe = dir / "pipe.slices";
    ASSERT_EQ(std::system(("mkfifo " + pipe).c_str()), 0);
    expectRefused(dir, pipe, "info " + pipe, "a named pipe, not a regular file");
    // A DICOM file of 2 GiB of zeros after its magic was read in full.
    const std::string zeros = dir / "zeros.dcm";
    {
        std::ofstream out(zeros, std::ios::binary);
        out << std::string(128, '\0') << "DICM";
    }
    fs::resize_file(zeros, (std::uint64_t(2) << 30) + 132);
    expectRefused(dir, zeros, "info " + zeros,
                  "larger than 1024 MiB, the limit of an RTSTRUCT file");
}

TEST(HostileInputs, EndlessStandardInputEndsAtTheTextLimit) {
#ifdef DFRECON_SANITIZE_BUILD
    GTEST_SKIP() << "a gigabyte through the sanitizers takes minutes; the release build checks it";
#else
    const TempDir dir("hostile-endless");
    const Result r = dfrecon::testing::runShell(
        dir.str(), "yes '# a comment' | " + std::string(DFRECON_BINARY) + " -q info -");
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("more than 1024 MiB of text, the limit of a .slices file"),
              std::string::npos)
        << r.err;
#endif
}

TEST(HostileInputs, InputsClaimingHugeGridsAreRefusedBeforeAllocating) {
    const TempDir dir("hostile-grids");
    const std::string torus = std::string(DFRECON_EXAMPLES) + "/torus.slices";
    // A CT series whose headers claim 65535 × 65535 × 3 voxels ran out of
    // memory (the NRRD route refused it).
    const std::string series = dir / "ct";
    fs::create_directories(series);
    dfrecon::testing::SyntheticImage image;
    image.rows = image.columns = 65535;
    image.withPixels = false;
    dfrecon::testing::writeSyntheticSeries(series, 3, 0, 2, image);
    expectRefused(dir, series, "rasterize " + torus + " --like " + series + " -o " + dir / "o.nrrd",
                  "its grid has more than 2147483648 voxels");
    const Result r = runCapped(dir, "rasterize " + torus + " --voxel-mm 0.02 -o " + dir / "o.nrrd");
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("--voxel-mm 0.02: the grid around the ROIs has"), std::string::npos)
        << r.err;
}

TEST(HostileInputs, HugeOrManyThingsStayWithinMemory) {
    const TempDir dir("hostile-memory-bounds");
    // 10 000 planes of one tiny contour: every plane's 256² field at once.
    // Without the cap (under the sanitizers) memory is not what is tested,
    // so 1 000 planes take the same code path in a tenth of the time.
#ifdef DFRECON_SANITIZE_BUILD
    const int planeCount = 1000;
#else
    const int planeCount = 10000;
#endif
    std::string tiny = "dfrecon-slices 1\nunits mm\nroi tiny\n";
    for (int k = 0; k < planeCount; ++k)
        tiny += "slice " + std::to_string(k) + "\ncontour 3\n0 0\n0.01 0\n0 0.01\n";
    const std::string planes = writeFile(dir, "tiny.slices", tiny);
    Result r = runCapped(dir, "reconstruct " + planes + " -o " + dir / "tiny.ply");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    // A 1 m cube against itself: samples grew with the area.
    const std::string cube = writeFile(dir, "cube.off",
                                       "OFF\n8 12 0\n0 0 0\n1000 0 0\n1000 1000 0\n0 1000 0\n"
                                       "0 0 1000\n1000 0 1000\n1000 1000 1000\n0 1000 1000\n"
                                       "3 0 2 1\n3 0 3 2\n3 4 5 6\n3 4 6 7\n3 0 1 5\n3 0 5 4\n"
                                       "3 1 2 6\n3 1 6 5\n3 2 3 7\n3 2 7 6\n3 3 0 4\n3 3 4 7\n");
    r = dfrecon::testing::runCli(dir.str(), "compare " + cube + " " + cube + " --json",
                                 memoryCap());
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("warning: --spacing 0.2 mm would take more than 8388608 samples"),
              std::string::npos)
        << r.err;
}

TEST(HostileInputs, AVertexOfTooManyTrianglesIsRefusedBeforeThePairwiseChecks) {
    // 10^5 triangles fanned around one vertex: every pair of them overlaps
    // in its box, and check, segment, sdm and compare never ended.
    const TempDir dir("hostile-fan");
    std::ostringstream off;
    const int n = 20002;
    off << "OFF\n" << n + 1 << " " << n / 2 << " 0\n0 0 0\n";
    for (int k = 0; k < n; ++k)
        off << std::cos(2 * M_PI * k / n) << " " << std::sin(2 * M_PI * k / n) << " " << k % 2
            << "\n";
    for (int k = 1; k < n; k += 2) off << "3 0 " << k << " " << k + 1 << "\n";
    const std::string fan = writeFile(dir, "fan.off", off.str());
    for (const std::string& command :
         {"check " + fan, "segment " + fan + " -k 2 -o " + dir / "s.ply",
          "compare " + fan + " " + fan})
        expectRefused(dir, fan, command,
                      "vertex 0 is a corner of more than 10000 triangles, the most one vertex may "
                      "have");
}
