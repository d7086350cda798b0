#pragma once
// Mask stacks: a folder of per-slice label images (PNG or TIFF) described by a small JSON sidecar,
// stack.json, read into an axial LabelVolume. The sidecar format is in docs/formats.md.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "io/labels/LabelVolume.hpp"

namespace dfrecon {

/// The sidecar's file name inside a mask stack folder.
inline constexpr const char* kMaskStackSidecar = "stack.json";

/// The most images a stack may list.
inline constexpr std::size_t kMaxMaskStackImages = 100000;

struct MaskStack {
    /// Axial, identity directions: voxel (i, j, k) is column i, row j of
    /// image k (row 0 first, rows running towards +y as in DICOM images),
    /// originMm the centre of pixel (0, 0) of the first image. For uneven
    /// slice positions spacingMm[2] is their mean gap; slicePositionsMm
    /// holds the exact ones.
    LabelVolume volume;
    std::vector<double> slicePositionsMm;            // z of each image, strictly increasing
    std::map<std::int32_t, std::string> labelNames;  // from the sidecar's "labels"
};

/// True when `path` names a mask stack: a folder holding stack.json, or a
/// file whose name ends in .json (case-insensitive). Touches only the
/// file system's metadata. O(1).
bool isMaskStackPath(const std::string& path);

/// Reads the stack whose sidecar is `path` (or `path`/stack.json for a
/// folder); image names are relative to the sidecar's folder. Images are
/// PNG or TIFF files read unchanged (io/images/ImageFiles) and must be 8- or 16-bit
/// single channel, all of one size. Throws InputError(file, 0, what is wrong) for
/// a missing or malformed sidecar (bad JSON, missing or mistyped keys,
/// spacing not a finite length from kMinVoxelSpacingMm to
/// kMaxAbsCoordinateMm, positions not strictly increasing or not one per
/// image or beyond kMaxAbsCoordinateMm, no images, more than
/// kMaxMaskStackImages images), missing or undecodable images, other pixel
/// types, images of different sizes, and stacks of more than
/// kMaxLabelVolumeVoxels voxels, over the memory budget or reaching beyond
/// the coordinate limit (checked after the first image, before the volume
/// is allocated). O(voxels).
MaskStack readMaskStack(const std::string& path);

}  // namespace dfrecon
