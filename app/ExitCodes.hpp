#pragma once
// The dfrecon program's exit codes (docs/cli.md lists them for users).
namespace dfrecon::app {

enum ExitCode : int {
    kExitOk = 0,
    kExitUsage = 1,     // bad command line: unknown option, missing argument, bad value
    kExitBadInput = 2,  // an input file is malformed or invalid (message says file:line)
    kExitRuntime = 3,   // OpenCL device/runtime failure, output not writable, out of memory
};

}  // namespace dfrecon::app
