#pragma once
// Which files one contour input consists of, with their sizes and SHA-256
// checksums: what a batch record keeps so that a rerun can tell whether an
// input changed since (docs/cli.md, "dfrecon batch").
#include <cstdint>
#include <string>
#include <vector>

namespace dfrecon {

struct InputFile {
    std::string path;  // relative to the input folder, or the file's own name
    std::uint64_t bytes = 0;
    std::string sha256;  // 64 lowercase hex digits
    bool operator==(const InputFile& o) const {
        return path == o.path && bytes == o.bytes && sha256 == o.sha256;
    }
};

/// The files that make up the input at `path`, sorted by path: a folder
/// (DICOM series, mask stack) gives every regular file under it; a header
/// that names other files (.nhdr, a mask stack's .json) gives itself and
/// every other regular file of its folder; any other file gives itself (a
/// label volume also the label table beside it, io/labels/LabelTable). A
/// path that does not exist gives none. Throws InputError naming the path
/// when a file cannot be read or is no regular file, before hashing
/// anything when there are more than kMaxInputFiles files or more than
/// kMaxInputBytes in all. O(total bytes).
std::vector<InputFile> inputFiles(const std::string& path);

/// As many as an image-series folder may hold (io/dicom/DicomImageSeries).
inline constexpr std::size_t kMaxInputFiles = 10000;
/// All files of one input together: 4 GiB, as one file of any kind may take
/// (io/files/RegularFile.hpp); a CT series and its structure set take under 1 GB.
inline constexpr std::uint64_t kMaxInputBytes = std::uint64_t(4) << 30;

}  // namespace dfrecon
