#pragma once
// How two structures agree, as contouring studies report it: volumes, Dice
// and Jaccard from the exact intersection volume (compare/OverlapVolume),
// Hausdorff, HD95, mean surface distance and surface Dice from exact closest
// points (field/SurfaceDistances, each within the sample spacing), the
// centroid distance, and for two contour stacks the planning system's
// per-plane overlap and added path length (compare/PlaneComparison).
#include <functional>
#include <optional>

#include "cl/Runtime.hpp"
#include "compare/OverlapVolume.hpp"
#include "compare/PlaneComparison.hpp"
#include "contours/ContourSet.hpp"
#include "field/SurfaceDistances.hpp"
#include "geometry/MeshCheck.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

/// One side of a comparison: a valid closed solid with its check (made once
/// and shared with the overlap), and its contours where it came from them.
struct ComparedSolid {
    TriangleSoup surface;
    MeshCheckReport check;
    const Roi* contours = nullptr;
};

struct CompareOptions {
    /// `{}`, `{spacing}` and `{spacing, tolerance}` (mm) as before a
    /// progress callback was added. Not explicit: `= {}` defaults use it.
    CompareOptions(double spacing = 0.2, double tolerance = 1)
        : spacingMm(spacing), toleranceMm(tolerance) {}
    double spacingMm;    // distance sample spacing: each distance within this of exact
    double toleranceMm;  // surface Dice and added path length tolerance
    /// Called with the fraction done after the overlap, the distances and
    /// the planes, for a progress bar; none: not called.
    std::function<void(double)> progress;
};

struct Comparison {
    Overlap overlap;
    SurfaceDistances distances;
    double centroidDistanceMm = 0;
    std::optional<PlaneComparison> planes;  // when both sides have contours
    double overlapSeconds = 0, distanceSeconds = 0, planeSeconds = 0;
};

/// Compares `a` and `b` (both valid closed solids: their checks say so).
/// Throws std::invalid_argument for a solid that is not valid, ClError on
/// device failure. O(corefinement + samples · log T).
Comparison compareSolids(ocl::Runtime& runtime, const ComparedSolid& a, const ComparedSolid& b,
                         const CompareOptions& options = {});

}  // namespace dfrecon
