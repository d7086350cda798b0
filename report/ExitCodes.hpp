#pragma once
// The dfrecon program's exit codes (docs/cli.md lists them for users).
#include <stdexcept>

namespace dfrecon {

enum ExitCode : int {
    kExitOk = 0,
    kExitUsage = 1,          // bad command line: unknown option, missing argument, bad value
    kExitBadInput = 2,       // an input file is malformed or invalid (message says file:line)
    kExitRuntime = 3,        // OpenCL device/runtime failure, output not writable, out of memory
    kExitInvalidResult = 4,  // a result is not what was asked for (reconstruct: a surface that
                             // is not a valid closed solid); reported, not written unless allowed
};

/// Thrown after a command has reported every result when one of them is
/// not valid; main() prints the message and exits kExitInvalidResult.
class InvalidResult : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

/// Thrown after a command that carries on past failing items (reconstruct
/// --all) has done and reported the rest: main() prints the message and
/// exits with the first failure's code.
class ItemsFailed : public std::runtime_error {
  public:
    ItemsFailed(const std::string& message, int exitCode)
        : std::runtime_error(message), exitCode_(exitCode) {}
    int exitCode() const { return exitCode_; }

  private:
    int exitCode_;
};

}  // namespace dfrecon
