#pragma once
// Label images as contour input: label volume files (NRRD, NIfTI) and mask
// stacks (images + stack.json) turned into ROIs of contour slices, for the
// command-line program's input dispatch, with the names and colours of a
// label table (io/labels/LabelTable).
#include <optional>
#include <string>

#include "contours/ContourSet.hpp"
#include "io/contours/ContourSource.hpp"
#include "io/labels/LabelVolume.hpp"

namespace dfrecon {

struct LabelInputOptions {
    /// A label table file naming and colouring the labels; empty: the
    /// volume's own (a .seg.nrrd's segments) or the one beside it
    /// (labelTableBeside), else names "label_N" and no colours.
    std::string labelTablePath;
    /// Contour a volume that looks like an intensity image (see
    /// intensityImageEvidence) instead of refusing it.
    bool acceptIntensityImages = false;
};

/// Why `volume` looks like an intensity image (a scan) rather than a label
/// map, or nullopt. A label map is piecewise constant: neighbouring voxels
/// differ only on region borders. The evidence is at least
/// kIntensityMinValues distinct non-zero values and, among pairs of
/// neighbouring voxels (along x and y) that are both non-zero, more than
/// kIntensityChangeFraction with different values. Atlases with hundreds of
/// labels change on a few percent of pairs; scans on most. O(voxels).
std::optional<std::string> intensityImageEvidence(const LabelVolume& volume);
inline constexpr std::size_t kIntensityMinValues = 32;
inline constexpr double kIntensityChangeFraction = 0.5;

/// The ROIs of a label input and where their names came from: the label
/// table's path, "segmentation header" for a volume carrying Slicer
/// segments, or "" (a mask stack's own names, or label_N).
struct LabelContours {
    ContourSet contours;
    std::string namesFrom;
};

/// Reads the label volume or mask stack of `source` (as decided by
/// contourSourceOf) and contours every label other than 0
/// (contoursFromLabels; a stack's label names and exact slice positions are
/// used). Names and colours: source's table when given; else a volume's own
/// segments (Slicer's .seg.nrrd); else the table found beside it. Throws
/// InputError for unreadable or invalid input, sheared volumes, a bad label
/// table, and volumes that look like intensity images unless
/// `acceptIntensityImages`. O(voxels).
LabelContours readLabelContours(const ContourSource& source, bool acceptIntensityImages = false);

/// The same for `path` and `options`, deciding the source here: the ROIs
/// alone. O(voxels).
ContourSet readLabelContours(const std::string& path, const LabelInputOptions& options = {});

}  // namespace dfrecon
