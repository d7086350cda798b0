#pragma once
// The list of work of `dfrecon batch`: a CSV file with a header row, or a
// JSON list of objects, with the keys `input` (required), `id`, `roi` and
// any option of report/ReconstructSettings named without its dashes
// (docs/cli.md, "dfrecon batch"). The whole manifest is checked before any
// entry runs, so a typo in row 4 000 costs seconds, not a day.
#include <cstddef>
#include <string>
#include <vector>

#include "report/ReconstructSettings.hpp"

namespace dfrecon::app {

struct ManifestEntry {
    std::size_t number = 0;            // 1-based position in the manifest
    std::string id;                    // the entry's folder name under the output folder
    std::string input;                 // as the manifest gives it
    std::string inputPath;             // resolved against the manifest's folder
    std::string roi;                   // a name or number; "" = every ROI with contours
    std::vector<GivenOption> options;  // in column or key order; where: "column C (KEY)" or
                                       // "entry N, key 'KEY'"
    int line = 0;                      // CSV: the line its row starts on; JSON: 0
    std::string where;                 // "FILE:LINE" (CSV) or "FILE: entry N" (JSON), for messages
};

/// Limits a manifest is held to; beyond them it is refused as bad input.
inline constexpr std::size_t kMaxManifestBytes = std::size_t(64) << 20;
inline constexpr std::size_t kMaxManifestEntries = 1000000;
inline constexpr std::size_t kMaxManifestValueBytes = 8192;
inline constexpr std::size_t kMaxManifestColumns = 256;

/// The manifest at `path`: JSON when its first byte after white space (and
/// a UTF-8 byte order mark) is '[', else CSV. Throws InputError for an
/// unreadable file or any problem parseManifest finds. O(file size).
std::vector<ManifestEntry> readManifest(const std::string& path);

/// The entries of manifest text `text` read from `file`, whose relative
/// inputs are resolved against `folder`. CSV: RFC 4180 (cells separated by
/// commas, quoted with "" where they hold commas, quotes or line breaks; a
/// quote inside a quoted cell doubled), LF or CRLF line ends, blank lines
/// skipped, spaces around unquoted cells dropped, an empty cell meaning the
/// default. Every problem is an InputError naming the place: "FILE:LINE:
/// column C: ..." for CSV, "FILE: entry N, key 'K': ..." for JSON (and
/// "FILE:LINE: ..." for JSON syntax): an unknown or repeated key, a missing
/// input, an id that is not a safe folder name (letters, digits, - _ .; not
/// starting with '.'; at most 120 bytes) or is used twice (also differing in
/// case only), an option value its command-line option refuses, a value
/// that is no string, number, boolean or null, the limits above. O(text).
std::vector<ManifestEntry> parseManifest(const std::string& text, const std::string& file,
                                         const std::string& folder);

}  // namespace dfrecon::app
