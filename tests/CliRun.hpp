#pragma once
// Runs the dfrecon program as a user does, through the shell, and captures
// what it says: the command-line tests' one way of starting it.
#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace dfrecon::testing {

struct CliResult {
    int exitCode = -1;  // -1: killed by a signal
    std::string out, err;
    double seconds = 0;
};

inline std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

/// Runs `shellCommand` through the shell, its stdout and stderr caught in
/// files of `scratchDir`; the exit code is that of its last command.
inline CliResult runShell(const std::string& scratchDir, const std::string& shellCommand) {
    const std::string out = scratchDir + "/stdout.txt", err = scratchDir + "/stderr.txt";
    const auto start = std::chrono::steady_clock::now();
    const int status = std::system(("(" + shellCommand + ") >" + out + " 2>" + err).c_str());
    CliResult result;
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = slurp(out);
    result.err = slurp(err);
    return result;
}

/// `DFRECON_BINARY args` with stdin from /dev/null; `shellPrefix` runs
/// first in the same shell (e.g. "ulimit -v N; "), and the program is
/// exec'd so limits apply to it.
inline CliResult runCli(const std::string& scratchDir, const std::string& args,
                        const std::string& shellPrefix = "") {
    return runShell(scratchDir, shellPrefix + "exec " + std::string(DFRECON_BINARY) + " " + args +
                                    " </dev/null");
}

}  // namespace dfrecon::testing
