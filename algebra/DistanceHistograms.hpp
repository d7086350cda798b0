#pragma once
// How an organ at risk lies around a target, as knowledge-based planning
// reads it: the overlap-volume histogram (OVH: the fraction of the OAR's
// volume within distance d of the target, d < 0 inside it; Kazhdan et al.,
// Med Phys 2009) and the distance-to-target histogram of the OAR's surface
// (the fraction of its area within d). Distances are exact signed
// distances to the target's closed surface (the closest-primitive kernel
// at free points, or its C++ twin); the OAR's volume is integrated over
// the centres of cubic cells (a cell counts when its centre lies inside
// the OAR's surface), its surface over cells no wider than a spacing
// (geometry/TriangleCells). The integrals converge as the cells shrink; the
// distances themselves are exact.
#include <cstddef>
#include <functional>
#include <vector>

#include "algebra/SolidField.hpp"
#include "cl/Runtime.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

struct DistanceHistogramOptions {
    double volumeStepMm = 0.5;      // edge of the cubic cells of the OAR's volume
    double surfaceSpacingMm = 0.5;  // farthest point of a surface cell from its sample
    /// Most volume cells; beyond, volumeStepMm grows until there are not
    /// more (the step used is reported).
    std::size_t maxVolumeCells = std::size_t(1) << 22;
    /// Most surface cells; beyond, surfaceSpacingMm grows until there are
    /// not more (the spacing used is reported): a tiny spacing would
    /// otherwise take memory without bound.
    std::size_t maxSurfaceCells = std::size_t(1) << 22;
    DistanceBackend backend = DistanceBackend::Device;
    /// Called with the fraction of the distance queries done (in batches),
    /// for a progress bar; none: not called.
    std::function<void(double)> progress;
};

/// Samples with a signed distance each and a weight (mm³ or mm²), sorted by
/// distance.
struct WeightedDistances {
    std::vector<double> distanceMm, weight;
    std::vector<double> cumulative;  // running sums of weight
    double total = 0;

    /// The fraction of the total weight at distance ≤ d. O(log n).
    double fractionWithin(double d) const;
    double minMm() const { return distanceMm.empty() ? 0 : distanceMm.front(); }
    double maxMm() const { return distanceMm.empty() ? 0 : distanceMm.back(); }
    /// The weighted mean distance. O(n).
    double meanMm() const;
};

struct DistanceHistograms {
    WeightedDistances volume;     // OVH: the OAR's volume cells, mm³
    WeightedDistances surface;    // the OAR's surface cells, mm²
    double volumeStepMm = 0;      // as used
    double surfaceSpacingMm = 0;  // as used
    double oarVolumeMm3 = 0;      // enclosed by its surface (the cells sum to about this)
    double oarAreaMm2 = 0;
};

/// Both histograms of `oar` against `target` (closed, outward surfaces in
/// one frame, mm). `runtime` may be null with DistanceBackend::Reference.
/// Throws std::invalid_argument for a surface that is not closed or steps
/// that are not positive. O(cells · log T) distance queries.
DistanceHistograms distanceHistograms(const TriangleSoup& oar, const TriangleSoup& target,
                                      const DistanceHistogramOptions& options,
                                      ocl::Runtime* runtime);

}  // namespace dfrecon
