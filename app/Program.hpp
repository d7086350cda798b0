#pragma once
// The dfrecon program: its root command line, every subcommand wired to it,
// and failures turned into exit codes. main.cpp only calls it, so CLI11's
// code is generated in the library's batches and not once more for the
// program (app/CMakeLists.txt says why that matters).

namespace dfrecon::app {

/// Parses `argv` and runs the subcommand it names. Returns the exit code
/// (report/ExitCodes.hpp, docs/cli.md); errors go to stderr. Cost: that of
/// the subcommand.
int runProgram(int argc, char** argv);

}  // namespace dfrecon::app
