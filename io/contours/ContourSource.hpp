#pragma once
// A contour input decided once, before any of it is read: where it is, which
// format it is (ContourFormat's table: by content, then by name), and, for a
// label volume, the label table that names its labels when the volume does
// not name them itself (the one given, else the one beside it). The readers
// take it as decided; none sniffs the format or looks for the table again.
#include <string>

#include "io/contours/ContourFormat.hpp"

namespace dfrecon {

struct ContourSource {
    std::string path;
    ContourFormat format = ContourFormat::Slices;
    /// A label volume's or mask stack's table: the one given (`tableGiven`),
    /// else for a label volume the one beside it (labelTableBeside), else
    /// empty. Unused for other formats.
    std::string labelTablePath;
    bool tableGiven = false;
};

/// `path` decided: its format, and the label table `givenLabelTable` (empty:
/// none given) or the one beside a label volume. O(1) file-system checks;
/// reads at most the first 132 bytes of a regular file.
ContourSource contourSourceOf(const std::string& path, const std::string& givenLabelTable = "");

}  // namespace dfrecon
