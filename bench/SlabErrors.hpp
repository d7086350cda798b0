#pragma once
// Distance errors split by where they lie between the contour planes, so the
// sag of a surface half-way between planes is visible next to its error at
// the planes (issue 17). Every error sample keeps its z; a sample between
// the first and last plane has a position t in [0, 1] within its slab.
#include <vector>

#include <nlohmann/json.hpp>

namespace dfrecon::bench {

/// An error measured at height z: the distance from a point of one surface
/// (reconstructed or true) to the other.
struct ErrorSample {
    double zMm = 0, errorMm = 0;
};

struct ErrorStats {
    std::size_t samples = 0;
    double meanMm = 0, p95Mm = 0, maxMm = 0;
};

struct SlabErrors {
    ErrorStats slab;       // every sample between the first and last plane
    ErrorStats nearPlane;  // t < 0.25 or t > 0.75 in its slab
    ErrorStats midSlab;    // 0.25 <= t <= 0.75
};

/// One figure of a class for a JSON line: null where the class holds no
/// sample (fewer than two planes).
inline nlohmann::json orNull(const ErrorStats& stats, double ErrorStats::*value) {
    return stats.samples == 0 ? nlohmann::json() : nlohmann::json(stats.*value);
}

/// Mean, 95th percentile (nearest rank) and maximum of each class; samples
/// below the first or above the last of `planesMm` (sorted, at least two
/// for any class to be filled) are left out, so caps do not weigh in.
SlabErrors splitBySlabPosition(const std::vector<ErrorSample>& samples,
                               const std::vector<double>& planesMm);

/// The same for an ROI that ends and starts again (contours/PlaneGaps):
/// `runsMm` holds each run's planes, sorted, the runs in order. Samples in
/// the planes left empty between two runs lie beyond an end plane like the
/// caps' and are left out as well; they are no slab.
SlabErrors splitBySlabPosition(const std::vector<ErrorSample>& samples,
                               const std::vector<std::vector<double>>& runsMm);

/// Whether z lies beyond every run's end planes (a cap's or a gap's sample).
bool beyondEveryRun(double zMm, const std::vector<std::vector<double>>& runsMm);

}  // namespace dfrecon::bench
