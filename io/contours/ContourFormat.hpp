#pragma once
// The contour inputs dfrecon reads, and the one table that maps them to
// names, extensions and the bytes that give them away (as io/mesh/MeshFormat
// does for meshes): app/Inputs picks its reader here, and every command's
// --help names the inputs from here.
//   slices       dfrecon .slices text                 .slices (any other name; "-")
//   rtstruct     DICOM RT Structure Set               .dcm, or "DICM" at byte 128
//   labelVolume  label map, one ROI per label         .nrrd .nhdr .nii .nii.gz
//   maskStack    image masks beside a stack.json      a folder holding stack.json, or the .json
// What each carries: docs/formats.md.
#include <string>
#include <vector>

namespace dfrecon {

enum class ContourFormat { Slices, RtStruct, LabelVolume, MaskStack };

/// The format of the contour input at `path`, by content first and then by
/// name: a regular file is DICOM when it carries "DICM" at byte 128, a
/// label volume when it starts with "NRRD000" or its first four bytes are
/// NIfTI's header size, 348 or 540 (either byte order); otherwise the name
/// decides (any letter case): .dcm; .nrrd .nhdr .nii .nii.gz; a folder
/// holding stack.json or a .json file (a mask stack). Anything else, and
/// "-" (standard input), is .slices, whose reader says what is wrong with
/// a file that is none of these. Reads at most the first 132 bytes, and
/// only of a regular file (never a pipe or a device). O(1).
ContourFormat contourFormatOf(const std::string& path);

/// True when `path` is a DICOM file: "DICM" at byte 128 of a regular
/// file, or a name ending in .dcm (any case). RTSTRUCTs and image series
/// both. O(1).
bool isDicomFile(const std::string& path);

/// The name reports give the format ("format" of `info --json`):
/// "dfrecon-slices 1", "DICOM RTSTRUCT", "label volume", "mask stack".
const char* contourFormatName(ContourFormat format);

/// The extensions that name label volumes: .nrrd .nhdr .nii .nii.gz.
const std::vector<std::string>& labelVolumeExtensions();

/// Whether `path` ends in one of labelVolumeExtensions() (any case). O(1).
bool hasLabelVolumeExtension(const std::string& path);

/// The help text of every command's contour input, made from the table
/// above. O(1).
const std::string& contourInputHelp();

}  // namespace dfrecon
