#pragma once
// A DICOM image series (the planning CT, or an MR) as the structure sets
// drawn on it refer to it: every image's SOP Class and Instance UIDs and
// plane, the series' study, patient and frame of reference, and its voxel
// grid. Pixel data are never read. Coordinates are patient LPS millimetres.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/Vec3.hpp"
#include "io/dicom/DicomAttributes.hpp"
#include "io/labels/LabelVolume.hpp"

namespace dfrecon {

/// One single-frame image of a series.
struct DicomImage {
    std::string path;
    std::string sopClassUid, sopInstanceUid;
    Vec3 positionMm;             // ImagePositionPatient: centre of the first pixel
    double planePositionMm = 0;  // dot(positionMm, series normal): where its plane lies
};

/// Every image of one series, sorted by increasing planePositionMm.
struct DicomImageSeries {
    DicomPatientStudy patientStudy;  // the first image's
    std::string seriesInstanceUid, frameOfReferenceUid, modality;
    int rows = 0, columns = 0;
    /// PixelSpacing (0028,0030) as DICOM orders it: [0] between rows (along
    /// columnDirection), [1] between columns (along rowDirection).
    double pixelSpacingMm[2] = {1, 1};
    /// ImageOrientationPatient (0020,0037): rowDirection is the direction of
    /// increasing column index, columnDirection that of increasing row index;
    /// both unit length and orthogonal (within 1e-4, then normalised).
    Vec3 rowDirection{1, 0, 0}, columnDirection{0, 1, 0};
    /// rowDirection × columnDirection: the direction in which planePositionMm grows.
    Vec3 normal{0, 0, 1};
    /// SliceThickness (0018,0050) of the first image where given (0: none);
    /// the grid spacing along the normal of a single-image series.
    double sliceThicknessMm = 0;
    std::vector<DicomImage> images;
    /// Files of the folder that were not images of this series, with why
    /// ("not DICOM", "RT Structure Set Storage, not an image", ...), for
    /// reports. At most one line per file.
    std::vector<std::string> skipped;
};

/// Bounds on what readDicomImageSeries reads.
struct DicomSeriesLimits {
    std::size_t maxFiles = 10'000;  // entries of the folder, DICOM or not
    /// Largest file looked at. Pixel data are not read, but the checks that
    /// run before DCMTK parses a file read all of it.
    std::uint64_t maxFileBytes = std::uint64_t(256) << 20;
};

/// Reads one series of single-frame images. `path` is a folder (its regular
/// files, not its subfolders, are read; files that are not DICOM, and DICOM
/// objects that are not images, such as an RTSTRUCT beside the CT, are
/// skipped and listed in `skipped`), or one image file, which stands for its
/// series: the images of its folder with its SeriesInstanceUID. Images of
/// other series are skipped when a file was given; in a folder they are an
/// error naming every series' UID, modality and image count.
///
/// Every image must carry SOPClassUID, SOPInstanceUID (no two alike),
/// Rows, Columns, PixelSpacing, ImagePositionPatient and
/// ImageOrientationPatient with finite values (coordinates within
/// kMaxAbsCoordinateMm, spacing at least kMinVoxelSpacingMm), one frame,
/// and the first image's StudyInstanceUID, FrameOfReferenceUID, Rows,
/// Columns, orientation (within 1e-4) and pixel spacing (within 1e-4 mm);
/// no two images may lie in one plane (within 0.01 mm). Throws InputError
/// naming the file, the tag and what is wrong for any of these, for a file
/// claiming to be DICOM (.dcm or the DICM magic) that DCMTK cannot read,
/// for sequences nested deeper than kMaxDicomNestingDepth, for a folder
/// with more than limits.maxFiles entries or no images, and for a file
/// over limits.maxFileBytes. O(total header bytes + n log n) for n images;
/// memory O(n) beyond one file's header at a time.
DicomImageSeries readDicomImageSeries(const std::string& path,
                                      const DicomSeriesLimits& limits = {});

/// The voxel grid of `series`, as a label volume on it would have:
/// size {columns, rows, images}, spacing {pixelSpacingMm[1],
/// pixelSpacingMm[0], gap between planes}, directions {rowDirection,
/// columnDirection, normal}, origin the first (lowest) image's position.
/// A single image takes sliceThicknessMm as its third spacing. Throws
/// InputError (naming the first image's folder) when the planes are not
/// evenly spaced (gaps differing by more than 0.01 mm), when an image's
/// position does not lie on the line from the first along the normal
/// (within 0.01 mm: a tilted gantry's stack is not a grid), or when a
/// single image has no SliceThickness. O(images).
VolumeGeometry gridOf(const DicomImageSeries& series);

/// The image whose plane holds every point in `pointsMm` (each within
/// `toleranceMm` of the plane along the series normal), or nullptr: contours
/// in no image plane, or across planes (contours at an angle to the
/// images). O(points + log images).
const DicomImage* imageHolding(const DicomImageSeries& series, const std::vector<Vec3>& pointsMm,
                               double toleranceMm);

}  // namespace dfrecon
