#pragma once
// How deep a DICOM file nests its sequences, found before DCMTK parses it.
// DCMTK's parser recurses once per sequence and item: a file of 100 000
// nested sequences (3.6 MB) exhausts the stack, and no parser option bounds
// it. This walk reads the element stream once, iteratively, with a fixed
// buffer: the File Meta Information, then the data set in its transfer
// syntax (implicit or explicit VR, little or big endian, deflated), item
// and sequence delimiters, defined and undefined lengths, encapsulated
// pixel data, and UN values of undefined length (implicit VR inside). A
// value of another VR that starts with an item tag is walked as a sequence
// too (DCMTK may read it as one), and skipped as opaque where it turns out
// not to be one. Where the stream is malformed outside such a value the
// walk stops: DCMTK refuses the file itself there.
#include <cstddef>
#include <string>

namespace dfrecon {

/// Throws InputError naming `path` when its sequences nest deeper than
/// `maxDepth` (kMaxDicomNestingDepth, io/files/InputLimits.hpp), or when it is
/// not a regular file (a FIFO would block the parser); a missing file is
/// left for the parser to report. O(file size) time (values are skipped, not
/// read), O(maxDepth) memory.
void checkDicomNesting(const std::string& path, std::size_t maxDepth);

}  // namespace dfrecon
