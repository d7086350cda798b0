#include "simplify/SimplificationVerifier.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "field/SurfaceDistances.hpp"
#include "geometry/SurfaceMeasures.hpp"
#include "geometry/TriangleBvh.hpp"
#include "geometry/TriangleCells.hpp"

namespace dfrecon {

std::vector<Vec3> sampleTriangles(const TriangleSoup& soup, std::size_t count, unsigned seed) {
    std::vector<Vec3> samples;
    if (soup.triangles.empty()) return samples;
    std::vector<double> cumulative;
    double total = 0;
    for (const auto& t : soup.triangles) {
        total += 0.5 * length(cross(soup.points[t[1]] - soup.points[t[0]],
                                    soup.points[t[2]] - soup.points[t[0]]));
        cumulative.push_back(total);
    }
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> u(0, 1);
    for (std::size_t k = 0; k < count; ++k) {
        const std::size_t t =
            std::size_t(std::lower_bound(cumulative.begin(), cumulative.end(), u(random) * total) -
                        cumulative.begin());
        const auto& tri = soup.triangles[std::min(t, soup.triangles.size() - 1)];
        double a = u(random), b = u(random);
        if (a + b > 1) a = 1 - a, b = 1 - b;
        const Vec3 p0 = soup.points[tri[0]];
        samples.push_back(p0 + a * (soup.points[tri[1]] - p0) + b * (soup.points[tri[2]] - p0));
    }
    return samples;
}

SampledDistance distanceToSurface(const std::vector<Vec3>& points, const TriangleSoup& surface) {
    if (points.empty()) return {};
    return distanceToSurface(points, TriangleBvh(surface));
}

SampledDistance distanceToSurface(const std::vector<Vec3>& points, const TriangleBvh& bvh) {
    SampledDistance d;
    if (points.empty()) return d;
    double sum = 0;
    for (const Vec3& p : points) {
        const double e = bvh.nearest(p).distance;
        d.maxMm = std::max(d.maxMm, e);
        sum += e;
    }
    d.samples = points.size();
    d.meanMm = sum / double(points.size());
    return d;
}

namespace {

// twoSidedDistance over hierarchies built once, which verifySimplification
// also measures the contours against.
TwoSidedDistance twoSidedDistance(const TriangleSoup& a, const TriangleBvh& bvhA,
                                  const TriangleSoup& b, const TriangleBvh& bvhB,
                                  std::size_t samplesPerSurface) {
    TwoSidedDistance d;
    if (a.triangles.empty() || b.triangles.empty()) return d;
    // Started below the spacing that gives samplesPerSurface cells (a cell
    // covers about 1.3 spacing²), so the budget decides it.
    const double areaMm2 = std::max(measureSurface(a).areaMm2, measureSurface(b).areaMm2);
    const std::size_t budget = std::clamp<std::size_t>(samplesPerSurface, 1, kMaxDistanceSamples);
    d.spacingMm = cellSpacingWithinBudget(
        {&a, &b}, std::max(1e-6, 0.5 * std::sqrt(areaMm2 / double(budget))), budget);
    const SurfaceDistances cells = surfaceDistances(a, bvhA, b, bvhB, d.spacingMm);
    const auto withVertices = [](const DirectedDistances& sampled,
                                 const SampledDistance& vertices) {
        SampledDistance both;
        both.maxMm = std::max(sampled.maxMm, vertices.maxMm);
        both.meanMm = sampled.meanMm;
        both.samples = sampled.samples + vertices.samples;
        return both;
    };
    d.aToB = withVertices(cells.aToB, distanceToSurface(a.points, bvhB));
    d.bToA = withVertices(cells.bToA, distanceToSurface(b.points, bvhA));
    return d;
}

}  // namespace

TwoSidedDistance twoSidedDistance(const TriangleSoup& a, const TriangleSoup& b,
                                  std::size_t samplesPerSurface) {
    if (a.triangles.empty() || b.triangles.empty()) return {};
    const TriangleBvh bvhA(a), bvhB(b);
    return twoSidedDistance(a, bvhA, b, bvhB, samplesPerSurface);
}

std::vector<Vec3> contourSamples(const Roi& roi, double stepMm) {
    double totalMm = 0;
    for (const Slice& slice : roi.slices)
        for (const Polygon& contour : slice.contours)
            for (std::size_t k = 0; k < contour.size(); ++k)
                totalMm += length(contour[(k + 1) % contour.size()] - contour[k]);
    stepMm = std::max(stepMm, totalMm / double(kMaxContourSamples));
    std::vector<Vec3> points;
    for (const Slice& slice : roi.slices)
        for (const Polygon& contour : slice.contours)
            for (std::size_t k = 0; k < contour.size(); ++k) {
                const Point2 a = contour[k], b = contour[(k + 1) % contour.size()];
                const double steps = std::max(1.0, std::ceil(length(b - a) / stepMm));
                for (int s = 0; s < int(steps); ++s) {
                    const Point2 p = a + (double(s) / steps) * (b - a);
                    points.push_back(roi.frame.toPatient({p.x, p.y, slice.zMm}));
                }
            }
    return points;
}

SimplificationDistance verifySimplification(const TriangleSoup& input, const TriangleSoup& result,
                                            const Roi* contours, double contourStepMm,
                                            std::size_t samplesPerSurface) {
    SimplificationDistance d;
    // Each hierarchy built once, for the cells, the vertices and the contours.
    const TriangleBvh inputBvh(input), resultBvh(result);
    d.surfaces = twoSidedDistance(input, inputBvh, result, resultBvh, samplesPerSurface);
    if (contours)
        d.contours = distanceToSurface(contourSamples(*contours, contourStepMm), resultBvh);
    return d;
}

}  // namespace dfrecon
