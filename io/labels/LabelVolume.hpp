#pragma once
// Label volumes (mask stacks, label maps) placed in patient space, read from
// NRRD (.nrrd, .nhdr) and NIfTI (.nii, .nii.gz) files and written as gzip
// NRRD files that 3D Slicer opens as label maps. Coordinates are DICOM
// patient LPS millimetres: x towards the patient's left, y posterior, z
// superior (head).
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "geometry/Vec3.hpp"
#include "geometry/VolumeGrid.hpp"

namespace dfrecon {

/// The most voxels a volume may have (2^31): a file claiming more is
/// rejected before anything is allocated.
inline constexpr std::uint64_t kMaxLabelVolumeVoxels = std::uint64_t(1) << 31;

/// The most layers a segmentation may have (3D Slicer makes one per set of
/// segments that overlap one another).
inline constexpr std::uint64_t kMaxLabelLayers = 256;

/// One integer label per voxel and layer; 0 is conventionally background.
/// A label map has one layer. A 3D Slicer segmentation whose segments
/// overlap keeps them on several layers (`SegmentN_Layer`; a 4-D .seg.nrrd
/// with the layers as its first, list axis), each layer a label map of
/// segments that do not overlap.
struct LabelVolume {
    VolumeGeometry geometry;
    /// layerCount · geometry.voxelCount() values: layer 0's voxels x
    /// fastest, then layer 1's, ...
    std::vector<std::int32_t> labels;
    int layerCount = 1;
    /// NRRD header key/value pairs (`key:=value`: a 3D Slicer
    /// segmentation's segment names and colours), in file order; read from
    /// and written to NRRD only.
    std::vector<std::pair<std::string, std::string>> keyValues;
};

/// The labels of layer `layer` of `volume` (its voxelCount() values). O(1).
inline const std::int32_t* layerLabels(const LabelVolume& volume, int layer) {
    return volume.labels.data() + std::size_t(layer) * volume.geometry.voxelCount();
}

/// Reads a 3-D label volume, choosing the format by the name's ending
/// (case-insensitive): .nrrd / .nhdr (NRRD, through teem: raw, gzip, ascii
/// or hex encoding, attached or detached header with one data file; a 4-D
/// file whose first axis is of kind `list` is read as that many layers, as
/// 3D Slicer writes segmentations whose segments overlap) or
/// .nii / .nii.gz (single-file NIfTI-1 or NIfTI-2, through niftilib).
/// Samples may be any integer type, or floating point holding integral
/// values within int32 (NIfTI scl_slope/scl_inter applied first).
/// Geometry is converted to LPS: NRRD `space` LPS as is, RAS and LAS
/// flipped, no space at all means identity axes with `spacings` (or 1 mm);
/// NIfTI uses the sform when sform_code > 0, else the qform, both RAS.
/// Throws InputError(path, 0, what is wrong) for a missing, unreadable,
/// unsupported or inconsistent file: not 3-D (a NIfTI file with more axes
/// is accepted when they all have size 1), more than kMaxLabelVolumeVoxels
/// voxels, samples and labels over the memory budget kMaxLabelVolumeBytes,
/// less data in the file than the header claims (both checked before the
/// data are allocated), a NIfTI vox_offset outside the file, spacing that is
/// not finite or below kMinVoxelSpacingMm (nan included, which the libraries
/// would turn into 1 mm), degenerate axes, a grid reaching beyond
/// kMaxAbsCoordinateMm (io/files/InputLimits.hpp), or a label that is not a
/// finite integer in int32 range (NaN floats included, which niftilib would
/// turn into 0). Thread-safe (the libraries' global state is guarded).
/// O(voxels).
LabelVolume readLabelVolume(const std::string& path);

/// Why a label map on `grid` may not be made ("" when it may): the
/// geometry checks of a label volume read from a file, and its voxels times
/// (4 + `bytesPerVoxel`) within kMaxLabelVolumeBytes, the budget a read
/// volume's samples and labels have. For writers that allocate a grid
/// someone else describes (rasterize --like CT, --voxel-mm), before they
/// allocate. O(1).
std::string labelGridProblem(const VolumeGeometry& grid, std::size_t bytesPerVoxel);

/// Writes `mask` (geometry.voxelCount() bytes, x fastest) as an attached
/// NRRD: type uchar, gzip encoding, `space: left-posterior-superior`,
/// `space directions` = spacingMm[a]·direction[a], `space origin` = originMm
/// (the NRRD origin is the centre of the first sample, as here),
/// `kinds: domain domain domain`. `path` must end in .nrrd. Atomic: on
/// failure nothing is left at `path`. Throws std::invalid_argument for a
/// mask or geometry that does not fit (see readLabelVolume's rules),
/// std::runtime_error when the file cannot be written. O(voxels).
void writeMaskNrrd(const std::string& path, const VolumeGeometry& geometry,
                   const std::vector<std::uint8_t>& mask);

/// Same for a label map, stored in the smallest of uchar, ushort, short and
/// int that holds every label, with volume.keyValues in the header; a
/// volume of several layers as a 4-D NRRD whose first axis (`kinds: list
/// domain domain domain`, space direction `none`) runs over the layers, as
/// 3D Slicer writes a segmentation with overlapping segments. O(voxels ·
/// layers).
void writeLabelNrrd(const std::string& path, const LabelVolume& volume);

/// Writes a label map by the extension of `path`: .nrrd as writeLabelNrrd,
/// .nii or .nii.gz as single-file NIfTI-1 (niftilib) in the same narrowest
/// type, sform and qform both set (code 1, scanner anatomical) to the
/// geometry in NIfTI's RAS, units mm; keyValues are not written there, and
/// a volume of several layers is refused (std::invalid_argument).
/// Atomic; throws std::invalid_argument for another extension or a volume
/// that does not fit, std::runtime_error on a failed write. O(voxels).
void writeLabelVolume(const std::string& path, const LabelVolume& volume);

}  // namespace dfrecon
