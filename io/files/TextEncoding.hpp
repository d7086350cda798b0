#pragma once
// Text from clinics is not always UTF-8: ROI names, file names and manifest
// cells typed on Windows arrive in Latin-1 or its superset Windows-1252
// ("Läsion", "Côté_D"). Everything dfrecon writes (JSON reports, .slices,
// label tables, NRRD headers) is UTF-8, so each reader turns its text into
// UTF-8 here, where the bytes are still known to be text of that file.
#include <string>
#include <string_view>

namespace dfrecon {

/// The length of the well-formed UTF-8 sequence starting at byte `i` of
/// `text` (1 for ASCII), or 0 where none starts (RFC 3629: no overlong
/// forms, no surrogates, nothing above U+10FFFF, not cut short). O(1).
std::size_t utf8SequenceLength(std::string_view text, std::size_t i);

/// Whether `text` is well-formed UTF-8 (utf8SequenceLength all through).
/// O(text).
bool isUtf8(std::string_view text);

/// `text` itself when it is UTF-8; otherwise every byte read as
/// Windows-1252 (Latin-1 with printable 0x80–0x9F; its five unassigned bytes
/// become U+FFFD) and written as UTF-8. Pure ASCII is unchanged either way.
/// Decide per name or per line, not per file: one Latin-1 name must not
/// turn the UTF-8 names beside it into mojibake. O(text).
std::string utf8FromLegacyText(std::string_view text);

/// `text` made UTF-8 as utf8FromLegacyText does, one line at a time
/// ('\n'-separated): for whole text files whose lines may come from
/// different sources. Bytes below 0x80, and so every line break, quote and
/// separator, stay where they were. O(text).
std::string utf8FromLegacyLines(std::string_view text);

}  // namespace dfrecon
