#pragma once
// What every subcommand does with its inputs: load a contour file (progress
// on a TTY, repair warnings on stderr unless quiet) and pick ROIs by name or
// number.
#include <string>
#include <vector>

#include "app/Commands.hpp"
#include "dfrecon/Contours.hpp"

namespace dfrecon::app {

/// Contours from any supported file, with what the format adds: the public
/// API's (dfrecon/Contours.hpp).
using ContourInput = ContoursRead;

/// How messages name standard input ("-").
inline constexpr const char* kStandardInputName = "<stdin>";

/// Loads and validates `path` by readContours (dfrecon/Contours.hpp), or "-",
/// .slices text from standard input (app/StandardStreams.hpp), with progress
/// on a TTY and the repairs' warnings on stderr unless quiet. With `onlyRois`
/// (the names or DICOM numbers a command was given) only the warnings about
/// those ROIs and the file as a whole are shown, and one line counts the
/// rest: a 40-ROI export read for one structure does not bury its warnings
/// under the others'. Throws InputError (exit 2) on bad input.
ContourInput loadContours(const std::string& path, const GlobalOptions& global,
                          const std::vector<std::string>& onlyRois = {});

/// The `onlyRois` of loadContours for a command given one ROI (`--roi`;
/// empty: none given, every warning shows).
inline std::vector<std::string> onlyRoi(const std::string& nameOrNumber) {
    return nameOrNumber.empty() ? std::vector<std::string>{}
                                : std::vector<std::string>{nameOrNumber};
}

/// The ROIs a command works on: `all` → every ROI with slices or a
/// defect (Roi::defect: the reader could not read it; the command reports
/// it); a name → that ROI (its defect, if it has one, is thrown:
/// exit 2) (or, failing a name, the ROI with that DICOM number); neither →
/// the only ROI. Throws std::invalid_argument (exit 1) naming the available
/// ROIs when the choice is missing, unknown or has no contours.
std::vector<const Roi*> selectRois(const ContourSet& contours, const std::string& name, bool all);

/// `name` made safe as part of a file name: letters, digits, - _ . kept,
/// anything else (and a leading dot, which would hide the file or make
/// "..") becomes _, at most kMaxStemBytes long.
std::string fileStem(const std::string& name);
inline constexpr std::size_t kMaxStemBytes = 120;

/// One file stem per ROI, unique among them even on case-insensitive file
/// systems: a stem that is one ROI's alone is kept; ROIs that share one get
/// _NUMBER (the ROI's number, or position), and _NUMBER_K where even that is
/// taken. Deterministic in the ROIs' order.
std::vector<std::string> uniqueFileStems(const std::vector<const Roi*>& rois);

}  // namespace dfrecon::app
