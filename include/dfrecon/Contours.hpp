#pragma once
// Contours in: every contour input dfrecon reads (.slices, DICOM RT
// Structure Sets, label volumes, mask stacks: io/contours/ContourFormat decides which
// by content, then by name), and structure sets built from points in memory.
// The command line's inputs go through readContours, so both read alike.
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "contours/ContourSet.hpp"
#include "geometry/Vec3.hpp"
#include "io/contours/ContourFormat.hpp"
#include "io/dicom/RtStruct.hpp"

namespace dfrecon {

struct ReadContoursOptions {
    /// Label volumes: a label table (.txt/.csv/.ctbl/.lut) naming the labels;
    /// "" looks beside the volume.
    std::string labelTable;
    /// Label volumes: contour every value even of a volume that looks like a
    /// scan's intensities.
    bool acceptIntensity = false;
    /// Receives the fraction of the file read (not every format reports it).
    std::function<void(double)> progress;
};

/// A contour input as read, with what its format adds.
struct ContoursRead {
    ContourFormat format = ContourFormat::Slices;
    ContourSet contours;
    std::vector<InputWarning> warnings;      // repairs made, in file order
    std::vector<RtStructRoiInfo> dicomRois;  // per ROI of `contours`, DICOM input only
    std::string labelTable;                  // label volumes: where ROI names came from ("" none)

    /// What DICOM reading found about `roi` (one of contours.rois), or nullptr. O(1).
    const RtStructRoiInfo* dicomInfo(const Roi& roi) const;
};

/// Reads `path` in the format contourFormatOf() finds. Every plane is read
/// as planning systems read it (geometry/PlaneReading: crossings by the
/// even-odd rule, folds, duplicates and contours of no area dropped, each
/// ROI's changes in Roi::reading), and where ROIs end and start again
/// across planes left empty is found (contours/PlaneGaps), with warnings.
/// An ROI whose contours cannot be used (a plane too complex to read,
/// non-planar contours) is kept with its `defect` and no slices, so the
/// file's other ROIs load. Throws InputError naming the file (and line or
/// tag) for bad input. O(input).
ContoursRead readContours(const std::string& path, const ReadContoursOptions& options = {});

/// Reads .slices text from `in`; `name` labels messages. As readContours
/// (no option of `options` applies to .slices text).
ContoursRead readSlicesStream(std::istream& in, const std::string& name,
                              const ReadContoursOptions& options = {});

/// One ROI given as points: each contour a closed polygon of at least three
/// points on one axial plane (constant z), in patient mm; the last point
/// need not repeat the first.
struct RoiPoints {
    std::string name;
    std::vector<std::vector<Vec3>> contours;
    std::optional<Rgb> colour;  // none: readers and viewers pick one
};

/// A structure set from points in memory, validated, repaired and oriented
/// exactly as a .slices file with these contours would be (repeated points
/// dropped, contours on one plane grouped, outer contours counter-clockwise,
/// holes clockwise). Messages name `source`, the ROI, the contour's index in
/// its list and the point, never a line of text. Throws InputError for a
/// contour with a non-finite coordinate, fewer than three points or points
/// off one axial plane (1e-6 mm); an ROI whose contours cross keeps it as
/// its `defect`, as readContours does. O(points).
ContoursRead structureSetFromPoints(const std::vector<RoiPoints>& rois,
                                    const std::string& source = "<points>",
                                    const ReadContoursOptions& options = {});

}  // namespace dfrecon
