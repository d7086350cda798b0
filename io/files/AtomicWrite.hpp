#pragma once
// Writing outputs so that a failed run never leaves a half-written file and
// never reports success for one. Every output file of dfrecon goes through
// here, whatever library formats it (OpenMesh, OpenVDB, DCMTK, teem, OpenCV,
// our own streams):
//
//  1. The library writes into memory (a memfd), reached through a symbolic
//     link named like the target (libraries pick the format from the
//     extension) inside a fresh private folder (mkdtemp, mode 0700) beside
//     the target. Libraries that ignore their own write errors cannot lose
//     bytes there.
//  2. We copy the bytes to a file created in that folder with O_CREAT |
//     O_EXCL | O_NOFOLLOW, checking every write, then fsync and close it
//     (checked: a full disk or a quota shows up here, as exit 3).
//  3. rename() puts it in place atomically; a symbolic link planted at the
//     target is replaced, never followed. The folder is fsynced, the
//     private folder removed.
//
// SIGINT, SIGTERM and SIGHUP remove the private folders of writes under way
// before the process dies of the signal (SIGKILL cannot be caught: such a
// run may leave a hidden `.NAME.dfrecon-XXXXXX` folder, never a file under
// the target's name).
#include <functional>
#include <iosfwd>
#include <string>

namespace dfrecon {

/// Calls `write(stagePath)`, where stagePath has the target's file name and
/// lives in a private folder, then moves the result to `path` as described
/// above. If `write` throws or returns false, or any step fails, nothing is
/// left behind, `path` is untouched, and the error propagates
/// (std::runtime_error "cannot write PATH: reason" for our own failures).
/// Throws std::invalid_argument for the path "-", which names standard
/// output on the command line, and for a target io/files/OutputTarget refuses (a
/// folder, device, FIFO or socket; an input of the run), before any write.
/// Memory: the file's size, held until it is copied. Thread-safe.
void writeAtomically(const std::string& path, const std::function<bool(const std::string&)>& write);

/// Same for stream output: `write(stream)`; a stream failure is an error.
void writeStreamAtomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);

}  // namespace dfrecon
