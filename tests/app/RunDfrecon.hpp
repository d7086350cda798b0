#pragma once
// Runs the dfrecon program as a user would, with its output caught in files
// of the test's scratch folder: what the command-line tests share.
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/TempDir.hpp"

namespace dfrecon::testing {

struct Run {
    int exitCode;
    std::string out, err;
};

inline std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

/// `dfrecon ARGS` through the shell (so `environment`, e.g. "A=1 B=2", may
/// set variables for it), stdin empty; waits for it. O(the run).
inline Run runDfrecon(const TempDir& dir, const std::string& args,
                      const std::string& environment = "") {
    const std::string out = dir / "stdout.txt", err = dir / "stderr.txt";
    const std::string command = environment + (environment.empty() ? "" : " ") +
                                std::string(DFRECON_BINARY) + " " + args + " >" + out + " 2>" +
                                err + " </dev/null";
    const int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

}  // namespace dfrecon::testing
