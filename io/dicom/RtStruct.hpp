#pragma once
// DICOM RT Structure Sets (RTSTRUCT, docs/formats.md): reading into the
// contour data model and writing it back. Coordinates are patient (LPS)
// millimetres, as in the file.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "contours/ContourSet.hpp"
#include "contours/InputError.hpp"
#include "io/dicom/DicomAttributes.hpp"
#include "io/dicom/DicomImageSeries.hpp"
#include "io/files/InputLimits.hpp"

namespace dfrecon {

/// How an ROI draws its holes, as found while reading.
enum class HoleConvention {
    None,     // no holes
    Nested,   // holes are separate contours inside their outer contour
    Keyhole,  // holes joined to their outer contour by a zero-width channel
    Xor,      // CLOSEDPLANAR_XOR contours, or contours sharing edges: exclusive or
};
/// The one list of the conventions' names, which reports print
/// (report/EnumNames.hpp reads it); holeConventionName reads it too.
inline constexpr std::array<std::pair<const char*, HoleConvention>, 4> kHoleConventionNames{{
    {"none", HoleConvention::None},
    {"nested", HoleConvention::Nested},
    {"keyhole", HoleConvention::Keyhole},
    {"xor", HoleConvention::Xor},
}};
/// The name of `convention` in kHoleConventionNames. O(1).
const char* holeConventionName(HoleConvention convention);

/// What reading found about one ROI beyond its contours.
struct RtStructRoiInfo {
    int number = 0;
    std::string name;
    std::size_t contoursRead = 0;     // closed planar contours accepted
    std::size_t contoursSkipped = 0;  // POINT, OPEN_PLANAR, OPEN_NONPLANAR, degenerate
    HoleConvention holes = HoleConvention::None;
    bool hasContourSequence = false;
};

/// Bounds that keep hostile files from exhausting memory or time.
struct RtStructLimits {
    /// The file: 2·10^7 points of three 16-character decimals take 1 GB.
    std::uint64_t maxFileBytes = std::uint64_t(1) << 30;
    std::size_t maxRois = 10'000;
    std::size_t maxContoursPerRoi = 1'000'000;
    std::size_t maxPointsTotal = 20'000'000;
    double maxAbsCoordinateMm = kMaxAbsCoordinateMm;
    std::size_t maxNestingDepth = kMaxDicomNestingDepth;     // checked before DCMTK parses
    std::size_t maxXorCrossings = kMaxXorCrossingsPerPlane;  // contours + crossings, per plane
    std::size_t maxXorCrossingsPerFile = kMaxXorCrossingsPerFile;  // and for the whole file
};

struct RtStructLoad {
    ContourSet contours;                // one Roi per StructureSetROISequence item, in file order
    std::vector<RtStructRoiInfo> rois;  // same order
    std::vector<InputWarning> warnings;
    std::string frameOfReferenceUid, studyInstanceUid, seriesInstanceUid, patientId, patientName;
};

/// Reads an RTSTRUCT file (Part 10 or raw dataset). ROIs come from
/// StructureSetROISequence joined to ROIContourSequence by ROI number;
/// CLOSED_PLANAR and CLOSEDPLANAR_XOR contours are grouped into planes
/// within kSamePlaneToleranceMm, keyholes are split, contours of a plane
/// that cross or share edges are combined by exclusive or (even-odd), and
/// contours are nested and oriented as Slice requires; non-axial stacks get
/// a PlaneFrame.
/// Other geometric types are skipped with a warning. Throws InputError
/// naming the tag for anything unreadable, missing, contradictory or over
/// `limits`. Linear in the file size plus validation.
RtStructLoad readRtStruct(const std::string& path, const RtStructLimits& limits = {});

/// The defined terms of RTROIInterpretedType (3006,00A4), PS3.3 C.8.8.8.
inline constexpr std::array<const char*, 24> kRoiInterpretedTypes{"EXTERNAL",
                                                                  "PTV",
                                                                  "CTV",
                                                                  "GTV",
                                                                  "TREATED_VOLUME",
                                                                  "IRRAD_VOLUME",
                                                                  "OAR",
                                                                  "BOLUS",
                                                                  "AVOIDANCE",
                                                                  "ORGAN",
                                                                  "MARKER",
                                                                  "REGISTRATION",
                                                                  "ISOCENTER",
                                                                  "CONTRAST_AGENT",
                                                                  "CAVITY",
                                                                  "BRACHY_CHANNEL",
                                                                  "BRACHY_ACCESSORY",
                                                                  "BRACHY_SRC_APP",
                                                                  "BRACHY_CHNL_SHLD",
                                                                  "SUPPORT",
                                                                  "FIXATION",
                                                                  "DOSE_REGION",
                                                                  "CONTROL",
                                                                  "DOSE_MEASUREMENT"};
/// Whether `type` is one of kRoiInterpretedTypes (exactly, upper case). O(1).
bool isRoiInterpretedType(const std::string& type);

/// The display colours of ROIs that come without one, in order
/// (displayColours): twelve hues far apart (red, green, blue, yellow, magenta, cyan, orange,
/// violet, spring green, pink, sky blue, olive), so that neighbouring
/// structures differ in a planning system's view.
inline constexpr std::array<Rgb, 12> kDefaultRoiColours{{{255, 0, 0},
                                                         {0, 200, 0},
                                                         {0, 96, 255},
                                                         {255, 255, 0},
                                                         {255, 0, 255},
                                                         {0, 220, 220},
                                                         {255, 128, 0},
                                                         {140, 60, 255},
                                                         {0, 255, 128},
                                                         {255, 105, 180},
                                                         {100, 180, 255},
                                                         {128, 128, 0}}};

/// Every ROI's display colour, as a written RTSTRUCT (and a report) gives
/// it: its own where it has one; else the first of kDefaultRoiColours that
/// no ROI of the set has and no ROI before it was given, then colours of
/// io/images/Colours' categorical scheme unused so far. So no two ROIs share a
/// colour unless the input gave them the same one: a margin is not drawn in
/// the yellow of another structure. O(R · (R + palette)).
std::vector<Rgb> displayColours(const ContourSet& set);

/// What an RTSTRUCT written by dfrecon refers to. Empty UIDs are generated:
/// without a study UID the structure set makes a study of its own, dated
/// when it is written; without a frame of reference UID, a frame of its own.
struct RtStructWriteOptions {
    DicomPatientStudy patientStudy;
    std::string frameOfReferenceUid;
    std::string structureSetLabel = "dfrecon";
    std::string seriesDescription = "dfrecon contours";
    /// RTROIInterpretedType of ROIs without one of their own (Roi::interpretedType).
    std::string defaultRoiType = "ORGAN";
    /// The image series the contours were drawn on: every image is listed in
    /// the Referenced Frame of Reference Sequence (RT Referenced Study >
    /// RT Referenced Series > Contour Image Sequence), and each contour whose
    /// points all lie within kSamePlaneToleranceMm of an image's plane refers
    /// to that image in its own Contour Image Sequence.
    std::optional<DicomImageSeries> imageSeries;
    /// Without imageSeries: the series a reference RTSTRUCT refers to (its
    /// RT Referenced Series, UIDs only: seriesInstanceUid and each image's
    /// SOP class and instance, no geometry), listed again in the frame of
    /// reference so that a structure set written back to the planning system
    /// stays on the images of its source. Contours are not matched to them.
    std::optional<DicomImageSeries> referencedSeries;
};

/// What `--like PATH` refers the output to. A folder, or a file that is an
/// image (it has ImagePositionPatient), is read as an image series
/// (readDicomImageSeries): its patient, study and frame of reference, and
/// the series itself. Any other DICOM file (an RTSTRUCT, an RT Plan) gives
/// its patient, study and frame of reference (FrameOfReferenceUID, else the
/// first ReferencedFrameOfReferenceSequence item's) and, for an RTSTRUCT,
/// the first series its frame refers to (referencedSeries). Throws
/// InputError naming the file and tag when it is not DICOM, has no frame of
/// reference or study, or is not a readable series.
RtStructWriteOptions referenceFrom(const std::string& dicomPath);

/// What writeRtStruct wrote.
struct RtStructWriteSummary {
    std::size_t rois = 0, contours = 0;
    /// With an image series: contours referring to an image, and those in no
    /// image's plane (they refer to none).
    std::size_t contoursOnImages = 0, contoursOffImages = 0;
    /// ROIs whose planes are not parallel to the images' (none of their
    /// contours can lie in an image plane), and ROIs with contours off the
    /// images, one line each.
    std::vector<std::string> warnings;
    /// The longest ContourData value (bytes). Beyond 65 534 (a contour of
    /// about 1 300 points) the file is written in implicit VR little endian,
    /// whose 32-bit lengths hold it; else in explicit VR little endian.
    std::size_t longestValueBytes = 0;
};

/// Writes `contours` as an RTSTRUCT (through a temporary file and a rename):
/// one ROI per Roi (its number, or its position from 1), CLOSED_PLANAR
/// contours in patient coordinates via each ROI's frame, DS values in at most
/// 16 characters, exactly the read values wherever they fit; ROIDisplayColor
/// Roi::colour, else kDefaultRoiColours by position; RTROIInterpretedType
/// Roi::interpretedType, else options.defaultRoiType. Throws
/// std::invalid_argument if defaultRoiType is not in kRoiInterpretedTypes,
/// std::runtime_error if `contours` has no ROIs (the IOD needs one) or
/// DCMTK cannot write. O(points + contours · log images).
RtStructWriteSummary writeRtStruct(const ContourSet& contours, const std::string& path,
                                   const RtStructWriteOptions& options = {});

/// The shortest decimal string (at most 16 characters, the DS limit) that
/// reads back as `value`, or the closest that fits.
std::string formatDecimalString(double value);

}  // namespace dfrecon
