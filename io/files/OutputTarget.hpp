#pragma once
// What an output path may name. A run must never lose data by writing:
// not an input it read (histogram -o onto its own contours), not a device
// node or FIFO given as output (replaced by a regular file), not a folder.
// Every file dfrecon writes passes here in io/files/AtomicWrite, whatever command
// or library wrote it; the program also checks its output options together
// before any work (app/OutputOptions), where two outputs of one command can
// be compared.
#include <string>

namespace dfrecon {

/// Why `path` cannot be replaced by a file: "" when it can (it is missing,
/// a regular file, or a symbolic link, which an atomic write replaces and
/// never follows). Otherwise "it is a folder", "... a character device",
/// "... a block device", "... a named pipe (FIFO)", "... a socket". O(1).
std::string whyNotAFileTarget(const std::string& path);

/// Whether `a` and `b` name one file: the same device and inode when both
/// exist (links and other spellings of one file included), else the same
/// path once made absolute and normal. O(1) system calls.
bool sameFile(const std::string& a, const std::string& b);

/// Whether `a` and `b` would be one file on a file system that ignores
/// letter case (macOS, Windows, many USB drives): the same folder and names
/// equal ignoring ASCII case. O(1) system calls.
bool sameFileIgnoringCase(const std::string& a, const std::string& b);

/// Throws std::invalid_argument (a usage error, exit 1) naming `path` when
/// it cannot be replaced by a file (whyNotAFileTarget) or, while inputs are
/// guarded, when it is a file this process has read (io/files/InputsInUse) and
/// not written itself before (a command may read back what it wrote, to
/// check it, and write it again). io/files/AtomicWrite calls it before every
/// write.
void checkOutputTarget(const std::string& path);

/// Turns on the check of outputs against the files read so far. The program
/// does (one process is one command); a library or Python user's process
/// reads and writes files across many calls, so it is off by default.
void guardInputsFromOutputs(bool on);

/// Records that this process wrote `path` (io/files/AtomicWrite, after each
/// write). Thread-safe.
void noteOutputWritten(const std::string& path);

}  // namespace dfrecon
