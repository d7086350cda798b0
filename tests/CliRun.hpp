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
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

/// `DFRECON_BINARY args` with stdin from /dev/null, stdout and stderr caught
/// in files of `scratchDir`; `shellPrefix` runs first in the same shell
/// (e.g. "ulimit -v N; "), and the program is exec'd so limits apply to it.
inline CliResult runCli(const std::string& scratchDir, const std::string& args,
                        const std::string& shellPrefix = "") {
    const std::string out = scratchDir + "/stdout.txt", err = scratchDir + "/stderr.txt";
    const std::string command = shellPrefix + "exec " + std::string(DFRECON_BINARY) + " " + args +
                                " >" + out + " 2>" + err + " </dev/null";
    const auto start = std::chrono::steady_clock::now();
    const int status = std::system(command.c_str());
    CliResult result;
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = slurp(out);
    result.err = slurp(err);
    return result;
}

}  // namespace dfrecon::testing
