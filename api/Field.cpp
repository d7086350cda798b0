#include "dfrecon/Field.hpp"

#include <chrono>
#include <stdexcept>

#include "field/FieldVolume.hpp"

namespace dfrecon {

namespace {

std::vector<Slice> planesWithContours(const Roi& roi) {
    if (roi.defect) throw *roi.defect;
    std::vector<Slice> slices;
    for (const Slice& s : roi.slices)
        if (!s.contours.empty()) slices.push_back(s);
    if (slices.empty()) throw std::invalid_argument("ROI '" + roi.name + "' has no contours");
    return slices;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

SliceFields roiSliceFields(ocl::Runtime& runtime, const Roi& roi, const RoiFieldOptions& options) {
    const std::vector<Slice> slices = planesWithContours(roi);
    return computeSliceFields(runtime, slices, gridForSlices(slices, options.pixelMm),
                              options.progress);
}

DistanceField3D roiDistanceField3D(ocl::Runtime& runtime, const Roi& roi,
                                   const RoiFieldOptions& options, double* fieldsSeconds,
                                   double* propagateSeconds) {
    const SpacingStats spacing = spacingOf(roi);
    auto start = std::chrono::steady_clock::now();
    const SliceFields fields = roiSliceFields(runtime, roi, options);
    if (fieldsSeconds) *fieldsSeconds = secondsSince(start);
    start = std::chrono::steady_clock::now();
    DistanceField3D field = layersFromSlices(fields, spacing.meanMm > 0 ? spacing.meanMm : 1.0);
    propagateAlongZ(runtime, field);
    if (propagateSeconds) *propagateSeconds = secondsSince(start);
    return field;
}

std::vector<std::size_t> roiVoxelsInside(ocl::Runtime& runtime, const Roi& roi,
                                         const VolumeGeometry& grid,
                                         const RoiFieldOptions& options) {
    return voxelsInside(roiDistanceField3D(runtime, roi, options), roi.frame, grid);
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

}  // namespace dfrecon
