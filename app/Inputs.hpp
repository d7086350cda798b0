#pragma once
// What every subcommand does with its inputs: load a contour file (progress
// on a TTY, repair warnings on stderr unless quiet) and pick ROIs by name or
// number.
#include <string>
#include <vector>

#include "app/Commands.hpp"
#include "io/ContourFormat.hpp"
#include "io/RtStruct.hpp"
#include "io/SlicesFile.hpp"

namespace dfrecon::app {

/// Contours from any supported file, with what the format adds.
struct ContourInput {
    ContourFormat kind = ContourFormat::Slices;
    std::string format;  // contourFormatName(kind): what reports call it
    ContourSet contours;
    std::vector<InputWarning> warnings;
    std::vector<RtStructRoiInfo> dicomRois;  // per ROI, DICOM input only
    std::string labelTable;                  // label volumes: where ROI names came from ("" none)

    /// What DICOM reading found about `roi` (one of contours.rois), or nullptr.
    const RtStructRoiInfo* dicomInfo(const Roi& roi) const;
};

/// How messages name standard input ("-").
inline constexpr const char* kStandardInputName = "<stdin>";

/// Loads and validates `path` in the format contourFormatOf() finds (content
/// first, then name): "-", .slices text from standard input
/// (app/StandardStreams.hpp); a label volume or mask stack, contoured per
/// label; a DICOM RT Structure Set; or a .slices file. Throws InputError
/// (exit 2) on bad input.
ContourInput loadContours(const std::string& path, const GlobalOptions& global);

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
