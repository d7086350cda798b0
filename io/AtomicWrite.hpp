#pragma once
// Writing outputs so that a failed run never leaves a half-written file: the
// content goes to a temporary file beside the target, which is renamed over
// the target only once complete.
#include <functional>
#include <iosfwd>
#include <string>

namespace dfrecon {

/// Calls `write(tempPath)` with a fresh temporary path in the target's folder
/// that keeps the target's extension (libraries like OpenMesh pick the format
/// from it), then renames it to `path`. If `write` throws or returns false,
/// the temporary file is removed, `path` is untouched, and the error
/// propagates (std::runtime_error "cannot write PATH" for false).
void writeAtomically(const std::string& path, const std::function<bool(const std::string&)>& write);

/// Same for stream output: `write(stream)`; a stream failure is an error.
void writeStreamAtomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);

}  // namespace dfrecon
