#pragma once
// What the NRRD and NIfTI halves of io/labels/LabelVolume share: sample types,
// checks of sizes, geometry and data, and conversion of samples to labels.
// Internal to io/; the API is io/labels/LabelVolume.hpp.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "io/labels/LabelVolume.hpp"

namespace dfrecon::labelvolume {

/// The sample types the readers accept (both formats' integer and
/// floating-point scalars).
enum class SampleType {
    Int8,
    UInt8,
    Int16,
    UInt16,
    Int32,
    UInt32,
    Int64,
    UInt64,
    Float32,
    Float64
};

/// Bytes per sample. O(1).
std::size_t sampleBytes(SampleType type);

/// value = slope·stored + intercept (NIfTI scl_slope/scl_inter); the
/// identity for NRRD.
struct LinearScale {
    double slope = 1, intercept = 0;
    bool identity() const { return slope == 1 && intercept == 0; }
};

/// The three axis sizes as ints after checking that the header declares
/// exactly three non-trivial axes: `sizes` lists every axis of the file
/// (fastest first); axes past the third must have size 1. Throws
/// InputError naming `path` for fewer than 3 axes, a fourth axis longer
/// than 1, a zero size, or more than kMaxLabelVolumeVoxels voxels (computed
/// without overflow). O(axes).
std::array<int, 3> checkedSizes(const std::string& path, const std::vector<std::uint64_t>& sizes);

/// Throws InputError naming `path` ("truncated: `what` can hold at most
/// ...") unless `availableBytes`, the most sample bytes the file can
/// decode to, reaches `neededBytes`. O(1).
void requireBytes(const std::string& path, std::uint64_t neededBytes, std::uint64_t availableBytes,
                  const char* what);

/// Geometry from axis steps in LPS (steps[a] = spacing·direction of axis
/// a, the columns of the index-to-world matrix) and the first voxel's
/// centre. Throws InputError naming `path` when a step is zero or not
/// finite, the axes are (nearly) parallel, or the origin is not finite.
/// O(1).
VolumeGeometry geometryFromSteps(const std::string& path, const std::array<int, 3>& size,
                                 const std::array<std::array<double, 3>, 3>& steps,
                                 const std::array<double, 3>& originMm);

/// Why `geometry` cannot describe a volume ("" when it can): sizes not
/// positive or too many voxels, spacing not finite or below
/// kMinVoxelSpacingMm, origin not finite, directions not unit vectors, axes
/// (nearly) parallel, or a corner of the grid beyond kMaxAbsCoordinateMm
/// (io/files/InputLimits.hpp). O(1).
std::string geometryProblem(const VolumeGeometry& geometry);

/// Why `voxels` samples of `sampleBytes` each, with a 32-bit label per
/// voxel, do not fit kMaxLabelVolumeBytes ("" when they do): checked from
/// the header, before anything is allocated. O(1).
std::string memoryProblem(std::uint64_t voxels, std::size_t sampleBytes);

/// The labels of geometry.voxelCount() samples of `type` at `data` (native
/// byte order, x fastest), scaled by `scale`. Throws InputError naming
/// `path` and the voxel for a value that is not finite, not an integer, or
/// outside int32. O(voxels).
std::vector<std::int32_t> labelsFromSamples(const std::string& path, const void* data,
                                            SampleType type, const VolumeGeometry& geometry,
                                            LinearScale scale);

/// Format halves, called by readLabelVolume and the writers once the name
/// and arguments are checked.
LabelVolume readNrrdLabelVolume(const std::string& path);
LabelVolume readNiftiLabelVolume(const std::string& path);
/// Writes geometry.voxelCount() · layerCount samples of `type` (UInt8,
/// UInt16, Int16 or Int32; a layer index fastest when layerCount > 1) as an
/// attached gzip NRRD in LPS, atomically: 3-D, or 4-D with the layers as a
/// first axis of kind list.
void writeNrrdSamples(const std::string& path, const VolumeGeometry& geometry, const void* data,
                      SampleType type,
                      const std::vector<std::pair<std::string, std::string>>& keyValues = {},
                      int layerCount = 1);

/// Layer-after-layer labels from labels with a layer index fastest (a
/// NRRD's list axis). O(values).
std::vector<std::int32_t> layersFromInterleaved(const std::vector<std::int32_t>& interleaved,
                                                std::uint64_t layerCount);
/// The same as a single-file NIfTI-1 (.nii or .nii.gz by the name), RAS
/// sform and qform, atomically.
void writeNiftiSamples(const std::string& path, const VolumeGeometry& geometry, const void* data,
                       SampleType type);

}  // namespace dfrecon::labelvolume
