#pragma once
// What an ROI name may hold, one rule for every reader and option that
// makes one, so that whatever is read or named can be written in every
// format and read back: well-formed UTF-8 (io/files/TextEncoding), at most
// kMaxRoiNameBytes, no control characters (a line break ends a .slices
// line, a tab or NUL breaks tables and DICOM's LO). Readers mend what a
// planning system may store (Latin-1 becomes UTF-8); options refuse.
#include <string>
#include <string_view>

namespace dfrecon {

/// "" when `name` is a valid ROI name; otherwise what is wrong ("is empty",
/// "is not UTF-8", "holds a control character (U+0009)", "is N bytes, over
/// the 256 a name may have"). O(length).
std::string roiNameProblem(std::string_view name);

/// `name` made valid: read as Windows-1252 where it is not UTF-8, control
/// characters as '_', cut at a character's start to kMaxRoiNameBytes, "_"
/// when empty. A valid name is returned as it is. O(length).
std::string mendedRoiName(std::string_view name);

}  // namespace dfrecon
