#include "bench/SlabErrors.hpp"

#include <algorithm>
#include <cmath>

namespace dfrecon::bench {

namespace {

ErrorStats statsOf(std::vector<double> errors) {
    ErrorStats stats;
    stats.samples = errors.size();
    if (errors.empty()) return stats;
    std::sort(errors.begin(), errors.end());
    double sum = 0;
    for (double e : errors) sum += e;
    stats.meanMm = sum / double(errors.size());
    // Nearest rank: the smallest error with at least 95 % of samples at or below it.
    const auto rank = std::size_t(std::ceil(0.95 * double(errors.size())));
    stats.p95Mm = errors[std::max<std::size_t>(rank, 1) - 1];
    stats.maxMm = errors.back();
    return stats;
}

}  // namespace

SlabErrors splitBySlabPosition(const std::vector<ErrorSample>& samples,
                               const std::vector<double>& planesMm) {
    return splitBySlabPosition(samples, std::vector<std::vector<double>>{planesMm});
}

SlabErrors splitBySlabPosition(const std::vector<ErrorSample>& samples,
                               const std::vector<std::vector<double>>& runsMm) {
    std::vector<double> slab, nearPlane, midSlab;
    for (const ErrorSample& s : samples)
        for (const std::vector<double>& planesMm : runsMm) {
            if (planesMm.size() < 2 || s.zMm < planesMm.front() || s.zMm > planesMm.back())
                continue;
            // The slab [z_k, z_k+1] holding z (the last one for z on the last plane).
            const auto above = std::upper_bound(planesMm.begin(), planesMm.end(), s.zMm);
            const std::size_t k =
                std::min<std::size_t>(std::size_t(above - planesMm.begin()), planesMm.size() - 1) -
                1;
            const double t = (s.zMm - planesMm[k]) / (planesMm[k + 1] - planesMm[k]);
            slab.push_back(s.errorMm);
            (t < 0.25 || t > 0.75 ? nearPlane : midSlab).push_back(s.errorMm);
            break;  // runs do not overlap: one slab per sample
        }
    return {statsOf(std::move(slab)), statsOf(std::move(nearPlane)), statsOf(std::move(midSlab))};
}

bool beyondEveryRun(double zMm, const std::vector<std::vector<double>>& runsMm) {
    for (const std::vector<double>& planesMm : runsMm)
        if (!planesMm.empty() && zMm >= planesMm.front() && zMm <= planesMm.back()) return false;
    return true;
}

}  // namespace dfrecon::bench
