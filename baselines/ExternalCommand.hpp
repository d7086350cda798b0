#pragma once
// Running another program for a baseline or a benchmark: plastimatch's
// distance map for the voxel margins, a benchmark route in a process of its
// own. The dfrecon program never runs one.
#include <string>
#include <vector>

namespace dfrecon {

/// Runs `arguments` (the first found on PATH unless it names a path), its
/// standard output and error written to `logPath`, and waits for it. Throws
/// std::runtime_error naming the command (with the end of the log) when it
/// cannot start or does not exit 0.
void runCommand(const std::vector<std::string>& arguments, const std::string& logPath);

}  // namespace dfrecon
