#pragma once
// The one gate every input file passes before anything opens it: it must be
// a regular file (after following links) no larger than its format allows.
// A named pipe would block the open for ever, a device (/dev/zero) would
// never end, a folder is no file, and a 100 GB sparse file would be read or
// hashed in full; each is refused as bad input naming the file instead.
#include <cstdint>
#include <string>

namespace dfrecon {

/// Largest input file of any kind (a label volume's samples, a DICOM file,
/// a mesh): 4 GiB, above every format's own limit (docs/cli.md, "Limits on
/// input"); a reader without a smaller limit of its own uses this one.
inline constexpr std::uint64_t kMaxInputFileBytes = std::uint64_t(4) << 30;

/// The size of `path` when it is a regular file of at most `maxBytes`.
/// Otherwise throws InputError(path, 0, ...) saying what it is instead ("a
/// named pipe, not a regular file") or that it is larger than the limit of
/// `what` (e.g. "a label table"). Opens nothing: O(1).
std::uint64_t checkRegularFile(const std::string& path, std::uint64_t maxBytes,
                               const std::string& what);

/// The whole of a file that passes checkRegularFile, read in one pass; a
/// file that grows past `maxBytes` while it is read is refused the same way.
/// O(size).
std::string readRegularFile(const std::string& path, std::uint64_t maxBytes,
                            const std::string& what);

/// Whether `path` is a regular file (after links): for the content sniffing
/// of format detection, which must not open a pipe or a device.
bool isRegularFile(const std::string& path);

}  // namespace dfrecon
