#include "dfrecon/Reconstruct.hpp"

#include <stdexcept>

#include "api/Stopwatch.hpp"
#include "geometry/OrderedParallel.hpp"

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
    // The reconstruction checked its surface as floats in the plane frame;
    // a rotated frame is checked again as written.
    roundPointsToFloat(result.surface);
    const Stopwatch watch;
    out.check = roi.frame.isIdentity() ? result.check : checkMesh(result.surface);
    out.checkSeconds = watch.total() + result.stats.checkSeconds;
    out.surface = std::move(result.surface);
    out.stats = result.stats;
    out.brokenPieces = std::move(result.brokenPieces);
    out.contourVolumeMm3 = contourVolumeMm3(roi);
    if (options.maxErrorMm > 0) {
        if (progress) progress("simplifying", -1);
        simplifyRoiSurface(runtime, roi, out, options.maxErrorMm);
    }
    return out;
}

void simplifyRoiSurface(ocl::Runtime& runtime, const Roi& roi, RoiSurface& surface,
                        double maxErrorMm) {
    SimplifyOptions simplify;
    simplify.maxErrorMm = maxErrorMm;
    surface.simplification = simplifyVerified(&runtime, surface.surface, simplify, &roi);
    surface.surface = std::move(surface.simplification->result.surface);
    roundPointsToFloat(surface.surface);
    const Stopwatch watch;
    surface.check = checkMesh(surface.surface);
    surface.checkSeconds += watch.total();
}

NeighbourSeparation keepNeighboursApart(ocl::Runtime& runtime, const std::vector<const Roi*>& rois,
                                        const std::vector<RoiSurface*>& surfaces,
                                        const NeighbourSeparationOptions& options) {
    std::vector<NeighbourSurface> taking;
    std::vector<std::size_t> indexOf;  // into rois, per taking entry
    for (std::size_t i = 0; i < rois.size(); ++i) {
        if (!surfaces[i] || !surfaces[i]->check.validSolid()) continue;
        NeighbourSurface roi{rois[i]->name, &surfaces[i]->surface, rois[i]->frame, {}};
        for (const Slice& slice : rois[i]->slices) roi.planeZMm.push_back(slice.zMm);
        taking.push_back(std::move(roi));
        indexOf.push_back(i);
    }
    NeighbourSeparation separation = keepNeighboursApart(&runtime, taking, options);
    for (NeighbourPair& pair : separation.pairs) {
        pair.a = indexOf[pair.a];
        pair.b = indexOf[pair.b];
    }
    // Moves change no triangle and leave no collision: the check stands but
    // for what the surface encloses.
    std::vector<std::optional<SurfaceMeasures>> measures(rois.size());
    for (std::size_t k = 0; k < taking.size(); ++k) {
        if (!separation.measures[k]) continue;
        MeshCheckReport& check = surfaces[indexOf[k]]->check;
        check.volumeMm3 = separation.measures[k]->volumeMm3;
        check.areaMm2 = separation.measures[k]->areaMm2;
        measures[indexOf[k]] = separation.measures[k];
    }
    separation.measures = std::move(measures);
    return separation;
}

std::vector<std::optional<Overlap>> neighbourOverlaps(const NeighbourSeparation& separation,
                                                      const std::vector<RoiSurface*>& surfaces) {
    std::vector<std::optional<Overlap>> overlaps(separation.pairs.size());
    forEachInOrder(
        separation.pairs.size(), defaultJobs(separation.pairs.size()),
        [&](std::size_t p, std::size_t) -> std::optional<Overlap> {
            const NeighbourPair& pair = separation.pairs[p];
            if (pair.overlapOnPlanes) return std::nullopt;
            const RoiSurface &a = *surfaces[pair.a], &b = *surfaces[pair.b];
            return overlapByFlux(a.surface, b.surface, a.check, b.check);
        },
        [&](std::size_t p, std::optional<Overlap> overlap) { overlaps[p] = std::move(overlap); });
    return overlaps;
}

}  // namespace dfrecon
