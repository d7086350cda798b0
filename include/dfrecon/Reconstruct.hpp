#pragma once
// An ROI's closed surface from its contours, in patient coordinates, checked
// as written (points rounded to float as mesh files hold them), simplified
// within a bound when asked: what `dfrecon reconstruct` and `batch` write
// per ROI, without the file and the report.
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cl/Runtime.hpp"
#include "compare/OverlapVolume.hpp"
#include "contours/ContourSet.hpp"
#include "dfrecon/Simplify.hpp"
#include "geometry/MeshCheck.hpp"
#include "geometry/TriangleSoup.hpp"
#include "neighbours/NeighbourSeparation.hpp"
#include "recon/Reconstruction.hpp"

namespace dfrecon {

struct RoiReconstructOptions {
    ReconstructionOptions reconstruction;  // pixel, caps, interpolation, depth (recon/)
    double maxErrorMm = 0;                 // > 0: simplify within this bound (dfrecon/Simplify)
};

struct RoiSurface {
    TriangleSoup surface;   // patient mm, outward, points as floats
    MeshCheckReport check;  // of `surface` as it is
    ReconstructionStats stats;
    double contourVolumeMm3 = 0;  // Σ area × thickness, as planning systems report it
    /// z ranges (mm, plane frame) of the slabs and caps that are not valid.
    std::vector<std::pair<double, double>> brokenPieces;
    /// When maxErrorMm > 0: its statistics and measured distances (its
    /// result.surface is moved into `surface`).
    std::optional<VerifiedSimplification> simplification;
    double checkSeconds = 0;  // the check of the result

    /// A valid closed solid, or open only where CapMode::None asked. O(1).
    bool usable(CapMode cap) const { return check.validSolid() || cap == CapMode::None; }
};

/// Progress of one ROI: the stage ("reconstructing", "simplifying") and the
/// fraction of it done (< 0 when unknown).
using RoiProgress = std::function<void(const std::string& stage, double fraction)>;

/// Reconstructs `roi` (recon/Reconstruction: valid by construction with flat
/// or dome caps), maps it to patient coordinates, simplifies it when
/// options.maxErrorMm > 0, rounds its points to float and checks it. Never
/// throws for an invalid result: `check` says so. Throws InputError for an
/// ROI with a defect, std::invalid_argument for one without contours,
/// ClError on device failure. Safe for several ROIs at once, one runtime
/// each. O(the reconstruction).
RoiSurface reconstructRoi(ocl::Runtime& runtime, const Roi& roi,
                          const RoiReconstructOptions& options = {},
                          const RoiProgress& progress = {});

/// Simplifies a reconstructed ROI's surface within maxErrorMm (> 0) as
/// reconstructRoi does when asked (dfrecon/Simplify, verified), then rounds
/// its points to float and checks it again. O(the simplification).
void simplifyRoiSurface(ocl::Runtime& runtime, const Roi& roi, RoiSurface& surface,
                        double maxErrorMm);

/// The ROIs of one structure set, reconstructed (without simplification,
/// the surfaces as reconstructRoi gives them): those whose contours overlap
/// on no plane they share are moved apart where they overlap between the
/// planes (neighbours/NeighbourSeparation; with options.move false only
/// found and measured), every contour point still a
/// vertex. Surfaces that are not valid solids are left out. Each changed
/// surface's check gets its new volume and area (its topology is the same
/// and it stays free of self-intersections). `rois[i]` made
/// `surfaces[i]`; null entries (ROIs that failed) are skipped. The report
/// indexes pairs by position in `rois`.
NeighbourSeparation keepNeighboursApart(ocl::Runtime& runtime, const std::vector<const Roi*>& rois,
                                        const std::vector<RoiSurface*>& surfaces,
                                        const NeighbourSeparationOptions& options = {});

/// The overlap of each pair of `separation` (keepNeighboursApart's, over the
/// same `surfaces`) as the surfaces are now, by compare's flux
/// (overlapByFlux: exact predicates, a stated bound); none for pairs whose
/// contours overlap on their planes (left as drawn) and for a pair the flux
/// cannot decide (no general position even with one moved), which would
/// take corefinement minutes. Pairs run on the free cores. O(one flux per
/// pair).
std::vector<std::optional<Overlap>> neighbourOverlaps(const NeighbourSeparation& separation,
                                                      const std::vector<RoiSurface*>& surfaces);

}  // namespace dfrecon
