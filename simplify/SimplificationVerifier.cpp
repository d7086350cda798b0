#include "simplify/SimplificationVerifier.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "geometry/TriangleBvh.hpp"

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
    SampledDistance d;
    if (points.empty()) return d;
    const TriangleBvh bvh(surface);
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

TwoSidedDistance twoSidedDistance(const TriangleSoup& a, const TriangleSoup& b,
                                  std::size_t samplesPerSurface, unsigned seed) {
    // Vertices too: a simplified surface's farthest points are often there.
    auto withVertices = [&](const TriangleSoup& s, unsigned k) {
        std::vector<Vec3> points = sampleTriangles(s, samplesPerSurface, k);
        points.insert(points.end(), s.points.begin(), s.points.end());
        return points;
    };
    return {distanceToSurface(withVertices(a, seed), b),
            distanceToSurface(withVertices(b, seed + 1), a)};
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
    d.surfaces = twoSidedDistance(input, result, samplesPerSurface);
    if (contours) d.contours = distanceToSurface(contourSamples(*contours, contourStepMm), result);
    return d;
}

}  // namespace dfrecon
