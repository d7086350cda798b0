#include "field/SurfaceDistances.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "field/ClosestPrimitives.hpp"
#include "geometry/SurfaceMeasures.hpp"
#include "geometry/TriangleBvh.hpp"
#include "geometry/TriangleCells.hpp"

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

// Calls visit(triangle, point, weightMm2) for every cell of `soup`'s
// triangles, triangle by triangle.
template <class Visit>
void forEachCellCentroid(const TriangleSoup& soup, double spacingMm, Visit&& visit) {
    for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
        const auto& tri = soup.triangles[t];
        forEachCell(soup.points[tri[0]], soup.points[tri[1]], soup.points[tri[2]], spacingMm,
                    [&](const Vec3& p, double weight) { visit(t, p, weight); });
    }
}

// The summary of one direction's samples, which it leaves sorted by
// distance for the pooled figures.
DirectedDistances summarise(std::vector<WeightedDistance>& samples, double toleranceMm) {
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

// The distances from every cell centroid of `from` to `to` over its
// hierarchy, each query starting from the last one's triangle.
std::vector<WeightedDistance> hostDistances(const TriangleSoup& from, const TriangleBvh& to,
                                            double spacingMm) {
    std::vector<WeightedDistance> samples;
    std::size_t hint = SIZE_MAX;
    forEachCellCentroid(from, spacingMm, [&](std::size_t, const Vec3& p, double weight) {
        const TriangleBvh::Nearest nearest = to.nearest(p, hint);
        hint = nearest.triangle;
        samples.push_back({nearest.distance, weight});
    });
    return samples;
}

// Samples go to the kernel in runs of this many (each about 100 bytes on
// the host and the device while it runs).
constexpr std::size_t kSamplesPerRun = std::size_t(1) << 20;

// The same distances from the closest-primitive kernel: object `from` of
// the scene asks object `to`. Runs hold whole triangles' samples, so each
// source triangle is culled once.
std::vector<WeightedDistance> deviceDistances(ClosestPrimitiveKernel& kernel,
                                              const TriangleSoup& from, std::uint32_t fromObject,
                                              int toObject, double spacingMm) {
    std::vector<WeightedDistance> samples;
    std::vector<SurfaceSample> run;
    std::vector<double> weights;
    DistanceQuery query;
    query.target = toObject;
    auto flush = [&] {
        const std::vector<ClosestPrimitive> answers = kernel.run(run, query);
        for (std::size_t k = 0; k < answers.size(); ++k)
            samples.push_back({std::abs(answers[k].distanceMm), weights[k]});
        run.clear();
        weights.clear();
    };
    std::size_t lastTriangle = SIZE_MAX;
    forEachCellCentroid(from, spacingMm, [&](std::size_t t, const Vec3& p, double weight) {
        if (t != lastTriangle && run.size() >= kSamplesPerRun) flush();
        lastTriangle = t;
        run.push_back({p, fromObject, std::uint32_t(t)});
        weights.push_back(weight);
    });
    if (!run.empty()) flush();
    return samples;
}

// The figures of both directions from their samples.
SurfaceDistances combine(const TriangleSoup& a, const TriangleSoup& b, double spacingMm,
                         double toleranceMm, std::vector<WeightedDistance> fromA,
                         std::vector<WeightedDistance> fromB) {
    SurfaceDistances d;
    d.spacingMm = spacingMm;
    d.toleranceMm = toleranceMm;
    d.areaAMm2 = measureSurface(a).areaMm2;
    d.areaBMm2 = measureSurface(b).areaMm2;
    d.aToB = summarise(fromA, toleranceMm);
    d.bToA = summarise(fromB, toleranceMm);
    d.hd95PooledMm = weightedPercentile95(fromA, fromB);
    return d;
}

void checkArguments(const TriangleSoup& a, const TriangleSoup& b, double spacingMm) {
    if (a.triangles.empty() || b.triangles.empty())
        throw std::invalid_argument("surface distances need two non-empty surfaces");
    if (!(spacingMm > 0)) throw std::invalid_argument("sample spacing must be > 0");
}

}  // namespace

double distanceSpacingWithinBudget(const TriangleSoup& a, const TriangleSoup& b, double spacingMm) {
    return cellSpacingWithinBudget({&a, &b}, spacingMm, kMaxDistanceSamples);
}

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
    checkArguments(a, b, spacingMm);
    spacingMm = distanceSpacingWithinBudget(a, b, spacingMm);
    const TriangleBvh bvhA(a), bvhB(b);
    return surfaceDistances(a, bvhA, b, bvhB, spacingMm, toleranceMm);
}

SurfaceDistances surfaceDistances(const TriangleSoup& a, const TriangleBvh& bvhA,
                                  const TriangleSoup& b, const TriangleBvh& bvhB, double spacingMm,
                                  double toleranceMm) {
    checkArguments(a, b, spacingMm);
    return combine(a, b, spacingMm, toleranceMm, hostDistances(a, bvhB, spacingMm),
                   hostDistances(b, bvhA, spacingMm));
}

SurfaceDistances surfaceDistances(ocl::Runtime& runtime, const TriangleSoup& a,
                                  const TriangleSoup& b, double spacingMm, double toleranceMm) {
    checkArguments(a, b, spacingMm);
    spacingMm = distanceSpacingWithinBudget(a, b, spacingMm);
    const SurfaceScene scene({a, b});
    ClosestPrimitiveKernel kernel(runtime, scene);
    return combine(a, b, spacingMm, toleranceMm, deviceDistances(kernel, a, 0, 1, spacingMm),
                   deviceDistances(kernel, b, 1, 0, spacingMm));
}

}  // namespace dfrecon
