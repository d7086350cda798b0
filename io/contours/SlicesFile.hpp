#pragma once
// The `.slices` v1 text format (docs/formats.md): reading with validation and
// repair, writing that round-trips exactly.
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "contours/ContourSet.hpp"
#include "contours/InputError.hpp"

namespace dfrecon {

/// Bounds that keep hostile or broken files from exhausting memory or time.
struct SlicesLimits {
    /// The whole text, file or standard input: 2·10^7 points as we write
    /// them take under 1 GB, and an endless stream (of comment lines, say)
    /// ends here in a few seconds.
    std::uint64_t maxBytes = std::uint64_t(1) << 30;
    std::size_t maxLineBytes = 64 * 1024;
    std::size_t maxPointsPerContour = 1'000'000;
    std::size_t maxPointsTotal = 20'000'000;
    std::size_t maxContoursPerSlice = 100'000;
    std::size_t maxSlicesPerRoi = 100'000;
    std::size_t maxRois = 10'000;
    double maxAbsCoordinateMm = 1e6;  // one kilometre: anything larger is a unit mix-up
};

/// Called as input is consumed, with the bytes read so far.
using SlicesProgress = std::function<void(std::uint64_t bytesRead)>;

struct SlicesLoad {
    ContourSet contours;
    std::vector<InputWarning> warnings;  // repairs made, in file order
};

/// Parses `.slices` text. `fileName` only labels messages. Throws InputError
/// ("file:line: problem") for any defect listed in docs/formats.md, except
/// that a geometric defect of one ROI's contours that reading does not
/// resolve (a plane too complex to search, crossings past the fill's limit)
/// is kept as that Roi's `defect`, with no slices, and the other ROIs load;
/// repairs
/// repeated points, unsorted slices and duplicated z with a warning; orients
/// contours by nesting depth (outer CCW, holes CW). Time and memory are
/// linear in the input for valid files and bounded by `limits` otherwise.
/// Each plane is read as planning systems read it (geometry/PlaneReading:
/// folds, duplicates and contours of no area dropped, contours crossing
/// themselves or each other replaced by their even-odd region), counted in
/// Roi::reading with one warning per ROI that changed.
SlicesLoad parseSlices(std::istream& in, const std::string& fileName,
                       const SlicesLimits& limits = {}, const SlicesProgress& progress = {});

/// Opens and parses a file; a missing or unreadable file is an InputError.
/// `progress`, if set, receives the fraction of the file read so far.
SlicesLoad readSlicesFile(const std::string& path, const SlicesLimits& limits = {},
                          const std::function<void(double)>& progress = {});

/// Writes `.slices` v1 text; numbers use the shortest form that reads back
/// to the same double, so parseSlices(formatSlices(x)) == x.
/// Throws std::invalid_argument for ROI names the format cannot hold.
void formatSlices(const ContourSet& contours, std::ostream& out);

/// formatSlices to `path` through a temporary file and a rename.
void writeSlicesFile(const ContourSet& contours, const std::string& path);

}  // namespace dfrecon
