#include "dfrecon/Reconstruct.hpp"

#include <stdexcept>

#include "api/Stopwatch.hpp"

namespace dfrecon {

RoiSurface reconstructRoi(ocl::Runtime& runtime, const Roi& roi,
                          const RoiReconstructOptions& options, const RoiProgress& progress) {
    if (roi.defect) throw *roi.defect;
    if (roi.slices.empty())
        throw std::invalid_argument("ROI '" + roi.name + "' has no closed planar contours");
    RoiSurface out;
    Reconstruction result = reconstructSurface(runtime, roi, options.reconstruction, [&](double f) {
        if (progress) progress("reconstructing", f);
    });
    // Sagittal, coronal and oblique stacks were reconstructed in their planes.
    toPatient(result.surface, roi.frame);
    if (options.maxErrorMm > 0) {
        if (progress) progress("simplifying", -1);
        SimplifyOptions simplify;
        simplify.maxErrorMm = options.maxErrorMm;
        out.simplification = simplifyVerified(&runtime, result.surface, simplify, &roi);
        result.surface = std::move(out.simplification->result.surface);
    }
    // The reconstruction checked its surface as floats in the plane frame;
    // a rotated frame or a simplified surface is checked again as written.
    roundPointsToFloat(result.surface);
    const Stopwatch watch;
    out.check =
        !out.simplification && roi.frame.isIdentity() ? result.check : checkMesh(result.surface);
    out.checkSeconds = watch.total() + result.stats.checkSeconds;
    out.surface = std::move(result.surface);
    out.stats = result.stats;
    out.brokenPieces = std::move(result.brokenPieces);
    out.contourVolumeMm3 = contourVolumeMm3(roi);
    return out;
}

}  // namespace dfrecon
