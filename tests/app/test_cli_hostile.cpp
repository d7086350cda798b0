// Hostile inputs (issue 16) as a user meets them: every one ends quickly,
// under a 3 GB address-space cap, with exit 2 and a message that starts
// with the file's name. The small ones live in tests/data/hostile with
// their expectations in cases.tsv; the large ones are generated here.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/TempDir.hpp"

namespace fs = std::filesystem;
using dfrecon::testing::TempDir;

namespace {

struct Result {
    int exitCode;
    std::string err;
    double seconds;
};

std::string slurp(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Runs dfrecon with `args` under the address-space cap the issue sets
// (not under AddressSanitizer, whose shadow memory needs far more).
Result run(const TempDir& dir, const std::string& args) {
    const std::string err = dir / "stderr.txt";
#ifdef DFRECON_SANITIZE_BUILD
    const std::string cap;
#else
    const std::string cap = "ulimit -v 3000000; ";
#endif
    const std::string command = cap + "exec " + std::string(DFRECON_BINARY) + " -q " + args +
                                " >/dev/null 2>" + err + " </dev/null";
    const auto start = std::chrono::steady_clock::now();
    const int status = std::system(command.c_str());
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(err), seconds};
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    for (std::size_t at = text.find(from); at != std::string::npos;
         at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
    return text;
}

// Exit 2 within two seconds, stderr "dfrecon: FILE..." saying `fragment`.
void expectRefused(const TempDir& dir, const std::string& file, const std::string& args,
                   const std::string& fragment, int exitCode = 2) {
    const Result r = run(dir, args);
    EXPECT_EQ(r.exitCode, exitCode) << args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("dfrecon: " + file, 0), 0u) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << args << "\n" << r.err;
    EXPECT_LT(r.seconds, 2.0) << args;
}

// Replays the lines of cases.tsv whose file starts with `prefix`; returns
// how many.
int replayCorpus(const std::string& prefix) {
    const TempDir dir("hostile-" + prefix);
    const std::string corpus = std::string(DFRECON_TEST_DATA) + "/hostile/";
    std::ifstream cases(corpus + "cases.tsv");
    EXPECT_TRUE(cases) << "no cases.tsv in " << corpus;
    std::string line;
    int count = 0;
    while (std::getline(cases, line)) {
        if (line.empty() || line[0] == '#' || line.rfind(prefix, 0) != 0) continue;
        std::istringstream fields(line);
        std::string file, exitCode, fragment, args;
        std::getline(fields, file, '\t');
        std::getline(fields, exitCode, '\t');
        std::getline(fields, fragment, '\t');
        std::getline(fields, args);
        EXPECT_TRUE(fs::exists(corpus + file)) << line;
        const std::string out = dir / ("out" + std::to_string(count));
        expectRefused(dir, corpus + file,
                      replaced(replaced(args, "{in}", corpus + file), "{out}", out), fragment,
                      std::stoi(exitCode));
        ++count;
    }
    return count;
}

}  // namespace

TEST(HostileInputs, MeshCorpusEndsWithExitTwoNamingTheFile) {
    EXPECT_GE(replayCorpus("mesh-"), 10);
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
