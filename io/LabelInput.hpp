#pragma once
// Label images as contour input: label volume files (NRRD, NIfTI) and mask
// stacks (images + stack.json) turned into ROIs of contour slices, for the
// command-line program's input dispatch.
#include <string>

#include "io/ContourSet.hpp"

namespace dfrecon {

/// True when `path` names label input by its form: a name ending in .nrrd,
/// .nhdr, .nii or .nii.gz (case-insensitive), or a mask stack
/// (isMaskStackPath). Reads no file contents. O(1).
bool isLabelInputPath(const std::string& path);

/// Reads the label volume or mask stack at `path` and contours every label
/// other than 0 (contoursFromLabels; a stack's label names and exact slice
/// positions are used). Throws InputError for unreadable or invalid input
/// and for sheared volumes. O(voxels).
ContourSet readLabelContours(const std::string& path);

}  // namespace dfrecon
