#pragma once
// An ROI's distance fields (reconstruction paper §2.1, §6.1): the exact
// signed 2D field of every plane with each pixel's nearest contour
// primitive, and the 3D field those fields make when propagated along z
// (in-plane Euclidean distance + |dz|: never below the Euclidean distance),
// resampled to a regular volume. What `dfrecon fields` and `dfrecon field`
// compute, without the files.
#include <functional>

#include "cl/Runtime.hpp"
#include "contours/ContourSet.hpp"
#include "dfrecon/Reconstruct.hpp"
#include "field/DistanceField3D.hpp"
#include "field/Rasterization.hpp"
#include "field/SliceFields.hpp"
#include "io/volumes/LevelSetVdb.hpp"

namespace dfrecon {

struct RoiFieldOptions {
    /// Pixel (and x/y voxel) size, mm; <= 0: the ROI's extent plus margin
    /// fits field/SliceGrid's default grid.
    double pixelMm = 0;
    /// The volume's z step: false: half the smallest slice gap (slices and
    /// cap planes are then voxel layers); true: the pixel size (cubic voxels).
    bool isotropic = false;
    /// > 0: each contour is first simplified within this bound (reconstruction
    /// paper §2.3, recon/ContourSimplification): fewer segments, a field
    /// within the bound of the contours' own.
    double contourErrorMm = 0;
    std::function<void(double)> progress;  // fraction of the 2D fields done
};

/// What simplifying the contours first did.
struct ContourSimplificationSummary {
    double contourErrorMm = 0;
    std::size_t pointsBefore = 0, pointsAfter = 0;
    double maxDeviationMm = 0;  // the largest distance of a dropped point to its new edge
};

/// The planes a field is computed on: `roi`'s planes with contours, their
/// contours simplified within contourErrorMm when > 0 (`summary`, when
/// given, says how). Throws InputError for an ROI with a defect,
/// std::invalid_argument for one without contours. O(points).
std::vector<Slice> fieldPlanes(const Roi& roi, double contourErrorMm,
                               ContourSimplificationSummary* summary = nullptr);

/// The exact signed field of every plane of fieldPlanes(roi), on one grid
/// around them (plane coordinates, mm; negative inside), with each pixel's
/// nearest primitive. Throws as fieldPlanes, std::invalid_argument for a
/// grid beyond field/SliceGrid's limits, ClError on device failure.
/// O(pixels · log segments).
SliceFields roiSliceFields(ocl::Runtime& runtime, const Roi& roi,
                           const RoiFieldOptions& options = {});

/// The same for planes already chosen (fieldPlanes). O(pixels · log segments).
SliceFields sliceFieldsOf(ocl::Runtime& runtime, const std::vector<Slice>& planes,
                          const RoiFieldOptions& options = {});

/// The ROI's 3D field before resampling: roiSliceFields as layers,
/// propagated along z (ends closing half a spacing beyond the end slices,
/// as flat caps do). `seconds`, when given, receive the 2D fields' and the
/// propagation's times. Throws as roiSliceFields. O(layers · pixels).
DistanceField3D roiDistanceField3D(ocl::Runtime& runtime, const Roi& roi,
                                   const RoiFieldOptions& options = {},
                                   double* fieldsSeconds = nullptr,
                                   double* propagateSeconds = nullptr);

/// The voxels of `grid` (any reference grid: a CT's, a NIfTI's; or
/// gridAroundRois) whose centres lie inside `roi`, where its 3D field is
/// negative (field/Rasterization), as increasing linear indices; a centre
/// on a contour plane (within 0.01 mm) is inside exactly when it is inside
/// the plane's contours. Where the ROI ends and starts again (planes left
/// empty, contours/PlaneGaps) each run's voxels are joined. Throws as
/// roiSliceFields. O(field + voxels in its box).
std::vector<std::size_t> roiVoxelsInside(ocl::Runtime& runtime, const Roi& roi,
                                         const VolumeGeometry& grid,
                                         const RoiFieldOptions& options = {});

/// The voxels of `grid` whose centres lie inside `solid`, the ROI's
/// reconstructed surface (reconstructRoi of `roi`), as increasing linear
/// indices: ray parity against its triangles (field/Rasterization's
/// voxelsInsideSolid), so the voxels' volume converges to the surface's as
/// they shrink; a centre on a contour plane (within 0.01 mm) is inside
/// exactly when it is inside the plane's contours. Throws
/// std::invalid_argument when `solid` is not a valid closed solid (no
/// inside to find). O(triangles + voxels in the surface's box).
std::vector<std::size_t> roiSolidVoxelsInside(const Roi& roi, const RoiSurface& solid,
                                              const VolumeGeometry& grid);

struct RoiDistanceVolume {
    /// Values x fastest, then y, then z; origin and voxel in the ROI's plane
    /// frame (the identity for axial stacks; roi.frame maps to patient LPS).
    DenseDistanceVolume volume;
    double zStepMm = 0, sliceSpacingMm = 0;
    double fieldsSeconds = 0, propagateSeconds = 0;
};

/// The ROI's 3D distance volume: roiSliceFields, propagated along z
/// (field/DistanceField3D, ends closing half a spacing beyond the end
/// slices as flat caps do) and resampled (field/FieldVolume). Throws as
/// roiSliceFields. O(voxels).
RoiDistanceVolume roiDistanceVolume(ocl::Runtime& runtime, const Roi& roi,
                                    const RoiFieldOptions& options = {});

/// The exact Euclidean signed distance (mm, negative inside) from every
/// voxel centre of roiDistanceVolume's grid to the ROI's reconstructed
/// surface (dfrecon/Reconstruct with `surface`: a valid closed solid through
/// every contour), from the closest-primitive kernel at free points
/// (field/ClosestPrimitives: the nearest triangle, signed by its
/// pseudo-normal). Unlike roiDistanceVolume's propagated field it is the
/// true distance everywhere, so its level sets are exact margins. Throws as
/// roiSliceFields, and std::invalid_argument when the surface is not a
/// valid closed solid. O(reconstruction + voxels · log triangles).
RoiDistanceVolume roiEuclideanDistanceVolume(ocl::Runtime& runtime, const Roi& roi,
                                             const RoiFieldOptions& options = {},
                                             const RoiReconstructOptions& surface = {});

}  // namespace dfrecon
