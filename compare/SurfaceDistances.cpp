#include "compare/SurfaceDistances.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "geometry/TriangleBvh.hpp"

namespace dfrecon {

namespace {

struct WeightedDistance {
    double distanceMm, weightMm2;
};

// The smallest distance below or at which 95 % of the weight of `a` and `b`
// together lies, both sorted by distance (a merge walk). O(|a| + |b|).
double weightedPercentile95(const std::vector<WeightedDistance>& a,
                            const std::vector<WeightedDistance>& b) {
    double total = 0;
    for (const auto* list : {&a, &b})
        for (const WeightedDistance& s : *list) total += s.weightMm2;
    double below = 0;
    for (std::size_t i = 0, j = 0; i < a.size() || j < b.size();) {
        const bool fromA = j == b.size() || (i < a.size() && a[i].distanceMm <= b[j].distanceMm);
        const WeightedDistance& s = fromA ? a[i++] : b[j++];
        below += s.weightMm2;
        if (below >= 0.95 * total) return s.distanceMm;
    }
    return 0;
}

// The lattice of a triangle: n × n similar cells, each edge at most
// spacingMm.
double latticeSteps(const Vec3& p0, const Vec3& p1, const Vec3& p2, double spacingMm) {
    const double longest = std::max({length(p1 - p0), length(p2 - p1), length(p0 - p2)});
    return std::max(1.0, std::ceil(longest / spacingMm));
}

double sampleCount(const TriangleSoup& soup, double spacingMm) {
    double count = 0;
    for (const auto& t : soup.triangles) {
        const double n =
            latticeSteps(soup.points[t[0]], soup.points[t[1]], soup.points[t[2]], spacingMm);
        count += (n + 1) * (n + 2) / 2;
    }
    return count;
}

// The spacing actually used: the one asked for, or coarser where that
// would take more than kMaxDistanceSamples samples on either surface (a
// metre-sized cube at 0.2 mm would take 10^8 and gigabytes).
double spacingWithinBudget(const TriangleSoup& a, const TriangleSoup& b, double spacingMm) {
    for (;;) {
        const double samples = std::max(sampleCount(a, spacingMm), sampleCount(b, spacingMm));
        if (samples <= double(kMaxDistanceSamples)) return spacingMm;
        // Samples fall with the square of the spacing, or slower (the
        // lattice's +1 per triangle): grow by the root, at least by 5 %.
        spacingMm *= std::max(1.05, std::sqrt(samples / double(kMaxDistanceSamples)));
    }
}

// The distances from every sample of `from` to `to`, summarised; the
// samples are left in `samples`, sorted by distance, for the pooled figures.
DirectedDistances directed(const TriangleSoup& from, const TriangleBvh& to, double spacingMm,
                           double toleranceMm, double& areaMm2,
                           std::vector<WeightedDistance>& samples) {
    samples.clear();
    areaMm2 = 0;
    for (const auto& t : from.triangles) {
        const Vec3 p0 = from.points[t[0]], p1 = from.points[t[1]], p2 = from.points[t[2]];
        const double area = 0.5 * length(cross(p1 - p0, p2 - p0));
        areaMm2 += area;
        const int n = int(latticeSteps(p0, p1, p2, spacingMm));
        const double weight = area / double((n + 1) * (n + 2) / 2);
        std::size_t hint = SIZE_MAX;
        for (int i = 0; i <= n; ++i)
            for (int j = 0; i + j <= n; ++j) {
                const double u = double(i) / n, v = double(j) / n;
                const Vec3 p = p0 + u * (p1 - p0) + v * (p2 - p0);
                const TriangleBvh::Nearest nearest = to.nearest(p, hint);
                hint = nearest.triangle;
                samples.push_back({nearest.distance, weight});
            }
    }
    DirectedDistances d;
    d.samples = samples.size();
    if (samples.empty()) return d;
    double total = 0, sum = 0;
    for (const WeightedDistance& s : samples) {
        total += s.weightMm2;
        sum += s.weightMm2 * s.distanceMm;
        d.maxMm = std::max(d.maxMm, s.distanceMm);
        if (s.distanceMm <= toleranceMm) d.areaWithinToleranceMm2 += s.weightMm2;
    }
    d.meanMm = total > 0 ? sum / total : 0;
    std::sort(samples.begin(), samples.end(),
              [](const WeightedDistance& x, const WeightedDistance& y) {
                  return x.distanceMm < y.distanceMm;
              });
    d.p95Mm = weightedPercentile95(samples, {});
    return d;
}

}  // namespace

double SurfaceDistances::hausdorffMm() const {
    return std::max(aToB.maxMm, bToA.maxMm);
}

double SurfaceDistances::hd95Mm() const {
    return std::max(aToB.p95Mm, bToA.p95Mm);
}

double SurfaceDistances::surfaceDice() const {
    const double total = areaAMm2 + areaBMm2;
    // The samples' weights sum to the areas up to rounding: kept within 1.
    return total > 0
               ? std::min(1.0, (aToB.areaWithinToleranceMm2 + bToA.areaWithinToleranceMm2) / total)
               : 1;
}

double SurfaceDistances::meanMm() const {
    const double total = areaAMm2 + areaBMm2;
    return total > 0 ? (aToB.meanMm * areaAMm2 + bToA.meanMm * areaBMm2) / total : 0;
}

SurfaceDistances surfaceDistances(const TriangleSoup& a, const TriangleSoup& b, double spacingMm,
                                  double toleranceMm) {
    if (a.triangles.empty() || b.triangles.empty())
        throw std::invalid_argument("surface distances need two non-empty surfaces");
    if (!(spacingMm > 0)) throw std::invalid_argument("sample spacing must be > 0");
    const TriangleBvh bvhA(a), bvhB(b);
    SurfaceDistances d;
    spacingMm = spacingWithinBudget(a, b, spacingMm);
    d.spacingMm = spacingMm;
    d.toleranceMm = toleranceMm;
    std::vector<WeightedDistance> fromA, fromB;
    d.aToB = directed(a, bvhB, spacingMm, toleranceMm, d.areaAMm2, fromA);
    d.bToA = directed(b, bvhA, spacingMm, toleranceMm, d.areaBMm2, fromB);
    d.hd95PooledMm = weightedPercentile95(fromA, fromB);
    return d;
}

}  // namespace dfrecon
