#include "dfrecon/Field.hpp"

#include <algorithm>
#include <iterator>
#include <stdexcept>

#include "api/Stopwatch.hpp"
#include "contours/PlaneGaps.hpp"
#include "field/ClosestPrimitives.hpp"
#include "field/FieldVolume.hpp"
#include "recon/ContourSimplification.hpp"

namespace dfrecon {

namespace {}  // namespace

std::vector<Slice> fieldPlanes(const Roi& roi, double contourErrorMm,
                               ContourSimplificationSummary* summary) {
    if (roi.defect) throw *roi.defect;
    std::vector<Slice> planes;
    for (const Slice& s : roi.slices)
        if (!s.contours.empty()) planes.push_back(s);
    if (planes.empty()) throw std::invalid_argument("ROI '" + roi.name + "' has no contours");
    if (contourErrorMm <= 0) return planes;
    ContourSimplificationSummary done;
    done.contourErrorMm = contourErrorMm;
    for (Slice& plane : planes) {
        const std::vector<SimplifiedContour> simplified =
            simplifySlice(plane.contours, contourErrorMm);
        for (std::size_t c = 0; c < plane.contours.size(); ++c) {
            done.pointsBefore += plane.contours[c].size();
            done.pointsAfter += simplified[c].points.size();
            for (double d : simplified[c].edgeDeviationMm)
                done.maxDeviationMm = std::max(done.maxDeviationMm, d);
            plane.contours[c] = simplified[c].points;
        }
    }
    if (summary) *summary = done;
    return planes;
}

SliceFields sliceFieldsOf(ocl::Runtime& runtime, const std::vector<Slice>& planes,
                          const RoiFieldOptions& options) {
    return computeSliceFields(runtime, planes, gridForSlices(planes, options.pixelMm),
                              options.progress);
}

SliceFields roiSliceFields(ocl::Runtime& runtime, const Roi& roi, const RoiFieldOptions& options) {
    return sliceFieldsOf(runtime, fieldPlanes(roi, options.contourErrorMm), options);
}

DistanceField3D roiDistanceField3D(ocl::Runtime& runtime, const Roi& roi,
                                   const RoiFieldOptions& options, double* fieldsSeconds,
                                   double* propagateSeconds) {
    const SpacingStats spacing = spacingOf(roi);
    Stopwatch watch;
    const SliceFields fields = roiSliceFields(runtime, roi, options);
    const double fieldsLap = watch.lap();
    if (fieldsSeconds) *fieldsSeconds = fieldsLap;
    // A lone plane stands for the image planes' spacing (contours/PlaneGaps).
    const double endSpacing = spacing.meanMm > 0              ? spacing.meanMm
                              : lonePlaneThicknessMm(roi) > 0 ? lonePlaneThicknessMm(roi)
                                                              : 1.0;
    DistanceField3D field = layersFromSlices(fields, endSpacing);
    propagateAlongZ(runtime, field);
    const double propagateLap = watch.lap();
    if (propagateSeconds) *propagateSeconds = propagateLap;
    return field;
}

std::vector<std::size_t> roiVoxelsInside(ocl::Runtime& runtime, const Roi& roi,
                                         const VolumeGeometry& grid,
                                         const RoiFieldOptions& options) {
    // Where planes are left empty the ROI ends and starts again: each run's
    // voxels, joined, as the surface joins its runs' solids.
    std::vector<std::size_t> inside;
    for (const Roi& run : planeRuns(roi)) {
        std::vector<std::size_t> part =
            voxelsInside(roiDistanceField3D(runtime, run, options), run.frame, grid, run.slices);
        std::vector<std::size_t> joined;
        joined.reserve(inside.size() + part.size());
        std::set_union(inside.begin(), inside.end(), part.begin(), part.end(),
                       std::back_inserter(joined));
        inside = std::move(joined);
    }
    return inside;
}

std::vector<std::size_t> roiSolidVoxelsInside(const Roi& roi, const RoiSurface& solid,
                                              const VolumeGeometry& grid) {
    if (!solid.check.validSolid())
        throw std::invalid_argument("the reconstructed surface of ROI '" + roi.name +
                                    "' is not a valid closed solid, so it has no inside");
    return voxelsInsideSolid(solid.surface, roi.frame, grid, roi.slices);
}

RoiDistanceVolume roiDistanceVolume(ocl::Runtime& runtime, const Roi& roi,
                                    const RoiFieldOptions& options) {
    RoiDistanceVolume out;
    const SpacingStats spacing = spacingOf(roi);
    out.sliceSpacingMm = spacing.meanMm;
    const DistanceField3D field =
        roiDistanceField3D(runtime, roi, options, &out.fieldsSeconds, &out.propagateSeconds);
    // Half the smallest gap puts every slice and both cap planes on a voxel
    // layer, whatever the gaps.
    out.zStepMm = options.isotropic   ? field.grid.pixelMm
                  : spacing.minMm > 0 ? spacing.minMm / 2
                                      : 0.5;
    out.volume = resampleAlongZ(field, out.zStepMm);
    return out;
}

RoiDistanceVolume roiEuclideanDistanceVolume(ocl::Runtime& runtime, const Roi& roi,
                                             const RoiFieldOptions& options,
                                             const RoiReconstructOptions& surface) {
    RoiDistanceVolume out = roiDistanceVolume(runtime, roi, options);  // its grid
    const Stopwatch watch;
    RoiSurface solid = reconstructRoi(runtime, roi, surface);
    if (!solid.check.validSolid())
        throw std::invalid_argument("the reconstructed surface of ROI '" + roi.name +
                                    "' is not a valid closed solid, so its Euclidean distance "
                                    "has no sign");
    const SurfaceScene scene({std::move(solid.surface)});
    ClosestPrimitiveKernel kernel(runtime, scene);
    DenseDistanceVolume& v = out.volume;
    // A layer at a time: the points of one layer are a few hundred thousand.
    const std::size_t layer = std::size_t(v.nx) * std::size_t(v.ny);
    std::vector<Vec3> points(layer);
    for (int k = 0; k < v.nz; ++k) {
        for (int j = 0; j < v.ny; ++j)
            for (int i = 0; i < v.nx; ++i)
                points[std::size_t(j) * std::size_t(v.nx) + std::size_t(i)] = roi.frame.toPatient(
                    {v.originMm[0] + i * v.voxelMm[0], v.originMm[1] + j * v.voxelMm[1],
                     v.originMm[2] + k * v.voxelMm[2]});
        const std::vector<ClosestPrimitive> found = kernel.runAt(points);
        for (std::size_t n = 0; n < layer; ++n)
            v.valuesMm[std::size_t(k) * layer + n] = float(found[n].distanceMm);
    }
    out.fieldsSeconds += watch.total();
    out.propagateSeconds = 0;
    return out;
}

}  // namespace dfrecon
