#pragma once
// The contour-slice data model: structures (ROIs) made of planar slices, each
// slice a set of closed polygons. All coordinates in millimetres.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "contours/InputError.hpp"
#include "contours/Rgb.hpp"
#include "geometry/PlaneFrame.hpp"
#include "geometry/PlaneReading.hpp"
#include "geometry/Polygon.hpp"

namespace dfrecon {

/// The closed polygons of one plane z = zMm. After loading and
/// normaliseOrientation(), outer contours are counter-clockwise, holes
/// clockwise, islands inside holes counter-clockwise again.
struct Slice {
    double zMm = 0;
    std::vector<Polygon> contours;
};

/// One structure (organ, tumour, ...): slices sorted by increasing z, each z
/// at most once.
struct Roi {
    std::string name;
    std::optional<int> number;  // DICOM ROI Number, where the ROI came from DICOM
    std::optional<Rgb> colour;
    /// DICOM RTROIInterpretedType (ORGAN, PTV, ...) where the source gave
    /// one (an RTSTRUCT's RTROIObservationsSequence); empty otherwise, and
    /// the RTSTRUCT writer then writes its default. .slices files do not
    /// hold it.
    std::string interpretedType;
    std::vector<Slice> slices;
    PlaneFrame frame;  // slice coordinates → patient coordinates (identity: axial)
    /// DICOM Contour Slab Thickness where the source gave one (0: none); a
    /// single-slice ROI is a slab this thick.
    double slabThicknessMm = 0;
    /// Why this ROI could not be read (its slices are then empty), where a
    /// reader keeps the file's other ROIs: a clinical export with one bad
    /// contour loop still gives every other structure.
    std::optional<InputError> defect;
    /// What reading changed in the contours as the file held them
    /// (geometry/PlaneReading: repeated points, folds, duplicates,
    /// contours of no area, crossings resolved by the even-odd rule),
    /// summed over the planes; reports list it per ROI.
    PlaneReadingCounts reading;
    /// Where the ROI ends and starts again (contours/PlaneGaps): indices of
    /// the slices that begin a new run because image planes with no
    /// contour of this ROI lie between them and the slice before. Empty:
    /// one run.
    std::vector<std::size_t> restartsAt;
    /// The spacing of the image planes the ROI's stack lies on (the median
    /// gap between the planes of every ROI of its file on that stack), 0
    /// when unknown: the thickness of a plane alone in its run.
    double imagePlaneSpacingMm = 0;

    std::size_t contourCount() const;
    std::size_t pointCount() const;
};

struct ContourSet {
    std::vector<Roi> rois;

    /// The first ROI with this exact name, or nullptr.
    const Roi* findRoi(const std::string& name) const;
    /// The ROI with this DICOM ROI Number, or nullptr.
    const Roi* findRoiNumber(int number) const;
};

/// Longest ROI name, in bytes of UTF-8, that any reader accepts (.slices,
/// label tables, .seg.nrrd; RTSTRUCT names are cut here with a warning):
/// every writer can then write what was read, and read it back. DICOM's LO
/// holds 64 characters.
inline constexpr std::size_t kMaxRoiNameBytes = 256;

/// Nesting depth of each contour of a slice: 0 for contours inside no other,
/// 1 for holes, 2 for islands inside holes, ... Contours may touch but must
/// not cross. O(c² · n) for c contours of n points (bounding boxes prune).
std::vector<int> nestingDepths(const Slice& slice);

/// Reverses contours so outer ones (even depth) run counter-clockwise and
/// holes (odd depth) clockwise. Returns how many were reversed.
std::size_t normaliseOrientation(Slice& slice);

struct Extent3 {
    double min[3] = {0, 0, 0}, max[3] = {0, 0, 0};
    bool empty = true;
};
/// Bounding box of every contour point of the ROI in its plane coordinates
/// (z from the slices).
Extent3 extentOf(const Roi& roi);

/// Bounding box of every contour point of the ROI in patient LPS
/// coordinates (the plane frame applied; the same as extentOf for the
/// identity). O(points).
Extent3 patientExtentOf(const Roi& roi);

/// Re-expresses `roi` in `target`, a frame of the same planes (target.n =
/// ±roi.frame.n): points and plane positions become `target`'s coordinates,
/// slices stay sorted by increasing z, and contours keep their orientation
/// convention (all reversed when the map between the frames is a mirror).
/// Exact when both frames' axes are patient axes up to sign (coordinates are
/// then only permuted and negated). Throws std::invalid_argument when the
/// normals differ. O(points).
void changeFrame(Roi& roi, const PlaneFrame& target);

/// Gaps between planes that differ by no more than this are one spacing.
inline constexpr double kUniformSpacingToleranceMm = 1e-3;

/// Slice spacing statistics of an ROI (0 slices or 1 slice: all zero).
struct SpacingStats {
    double minMm = 0, maxMm = 0, meanMm = 0;
    bool uniform = true;  // max - min within kUniformSpacingToleranceMm
};
SpacingStats spacingOf(const Roi& roi);

/// The thickness each plane stands for, as planning systems weigh it: the
/// DICOM slab thickness when given (> 0), else the mean of the gaps to the
/// neighbouring planes (an end plane takes its one gap; a lone plane 0).
/// `planeZMm` sorted increasing. O(planes).
std::vector<double> planeThicknessesMm(const std::vector<double>& planeZMm, double slabThicknessMm);

/// The volume planning systems report for an ROI: the sum over its planes
/// of the contours' net area (holes subtracted) times the plane's thickness
/// — the DICOM slab thickness when given, else the mean of the gaps to the
/// neighbouring planes of its run (Roi::restartsAt: planes left empty
/// count nothing; an end plane takes its one gap; a plane alone in its run
/// the image planes' spacing, 0 when unknown). O(points).
double contourVolumeMm3(const Roi& roi);

}  // namespace dfrecon
