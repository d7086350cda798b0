#pragma once
// Label tables: what each value of a label volume stands for (a structure's
// name and display colour), in the files the tools beside dfrecon write and
// read:
//   ITK-SNAP label description (.txt)   IDX R G B A VIS MSH "LABEL"
//   FreeSurfer LUT / 3D Slicer colour table (.lut, .ctbl, .txt)
//                                       VALUE NAME R G B [A]
//   plain lists (AAL3, many atlases)    VALUE NAME [anything]
//   AAL (v4) lists                      ABBREVIATION NAME VALUE
//   3D Slicer segmentations (.seg.nrrd) SegmentN_LabelValue / _Name / _Color
//                                       in the NRRD header
// Blank lines and lines starting with '#' are skipped in the text forms.
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "contours/ContourSet.hpp"

namespace dfrecon {

/// One label's meaning; the colour is optional (plain lists have none).
struct LabelEntry {
    std::string name;
    std::optional<Rgb> colour;
};

/// Label value → meaning. Values not listed have no name.
using LabelTable = std::map<std::int32_t, LabelEntry>;

/// Most bytes of a label table file (FreeSurfer's full LUT is ~70 kB) and
/// of one name (every ROI name's limit, so whatever is read can be written).
inline constexpr std::uintmax_t kMaxLabelTableBytes = 16u << 20;
inline constexpr std::size_t kMaxLabelNameBytes = kMaxRoiNameBytes;

/// Reads a text label table in any of the forms above, recognised per line.
/// Throws InputError(path, line, what) for a missing or oversized file, a
/// line that fits no form, a value outside int32, a colour component
/// outside 0..255, an empty or over-long name, or one value listed twice.
/// O(file size · log entries).
LabelTable readLabelTable(const std::string& path);

/// The table of layer `layer` of a 3D Slicer segmentation of `layerCount`
/// layers, from its header (NRRD key/value pairs `SegmentN_LabelValue`,
/// `SegmentN_Name`, `SegmentN_Color` with components in 0..1,
/// `SegmentN_Layer`, 0 when missing): the segments on that layer; empty
/// when there are none. Throws InputError(path, 0, what) for a malformed
/// entry, a segment on a layer the volume does not have, or two segments of
/// one layer with one label value. O(pairs · log pairs).
LabelTable labelTableFromSegmentation(const std::string& path,
                                      const std::vector<std::pair<std::string, std::string>>& keys,
                                      int layer = 0, int layerCount = 1);

/// The NRRD header pairs of a Slicer segmentation for `table`, as Slicer
/// writes them: one segment per entry in value order, with its label value,
/// layer (`layerOf`'s entry, 0 for a value it lacks), name, colour (a
/// generated one where the entry has none) and extent
/// `0 size0-1 0 size1-1 0 size2-1`. O(entries · log entries).
std::vector<std::pair<std::string, std::string>> segmentationKeys(
    const LabelTable& table, const std::array<int, 3>& size,
    const std::map<std::int32_t, int>& layerOf = {});

/// Writes `table` atomically by the extension of `path`: .txt an ITK-SNAP
/// label description (with "Clear Label" 0 first, as ITK-SNAP writes it),
/// .ctbl or .lut a colour table `VALUE NAME R G B A` (names with spaces
/// written with underscores, which both formats need). Entries without a
/// colour get categoricalColour(value). Throws std::invalid_argument for
/// another extension, std::runtime_error on a failed write. O(entries).
void writeLabelTable(const std::string& path, const LabelTable& table);

/// `volumePath` without .nii.gz, .nii, .nrrd or .nhdr (and .seg before
/// them): STEM, to which the label table beside a volume adds its ending.
/// O(length).
std::string labelVolumeStem(const std::string& volumePath);

/// The label table that sits beside label volume `volumePath`: the first of
/// STEM.txt, STEM.ctbl, STEM.lut, STEM-labels.txt that exists (STEM:
/// labelVolumeStem); nullopt when none does. O(1) file-system checks.
std::optional<std::string> labelTableBeside(const std::string& volumePath);

}  // namespace dfrecon
