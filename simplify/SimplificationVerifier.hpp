#pragma once
// The verifier of simplification, independent of any distance field: how far
// a surface is from another surface, and from the original contour
// polylines, by dense sampling and exact point–triangle distances over a BVH.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "contours/ContourSet.hpp"
#include "geometry/TriangleBvh.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

/// `count` points distributed uniformly by area over the triangles of
/// `soup` (seeded, reproducible). O(T + count log T).
std::vector<Vec3> sampleTriangles(const TriangleSoup& soup, std::size_t count, unsigned seed);

struct SampledDistance {
    double maxMm = 0, meanMm = 0;
    std::size_t samples = 0;
};

/// Distances from `points` to the nearest point of `surface`.
/// O(T log T + points · log T) typically.
SampledDistance distanceToSurface(const std::vector<Vec3>& points, const TriangleSoup& surface);
/// The same over `surface`'s hierarchy, built by the caller. O(points · log T).
SampledDistance distanceToSurface(const std::vector<Vec3>& points, const TriangleBvh& surface);

/// Both directions between two surfaces, by the project's one surface
/// distance (field/SurfaceDistances): each surface cut into cells, about
/// `samplesPerSurface` of them (at least one per triangle), every point of
/// a cell within `spacingMm` of its sample, each sample's exact distance to
/// the other surface; and every vertex of each too (a simplified surface's
/// farthest points are often there). maxMm is the largest distance found,
/// within spacingMm below the exact Hausdorff distance; meanMm weighs the
/// cells by area. O((S + V) log T).
struct TwoSidedDistance {
    SampledDistance aToB, bToA;
    double spacingMm = 0;
    double maxMm() const { return aToB.maxMm > bToA.maxMm ? aToB.maxMm : bToA.maxMm; }
};
TwoSidedDistance twoSidedDistance(const TriangleSoup& a, const TriangleSoup& b,
                                  std::size_t samplesPerSurface);

/// Points along every contour of `roi` (every vertex, and along each edge
/// at most `stepMm` apart, or the step that gives kMaxContourSamples over
/// all contours where that is longer), at their slice's z, in patient
/// coordinates (through the ROI's frame). O(points + samples).
std::vector<Vec3> contourSamples(const Roi& roi, double stepMm);

/// Most samples contourSamples takes between vertices (100 MB): a step of
/// an eighth of a 1 µm bound along a metre of contour would take 8·10^9
/// points; a body outline's 200 m of contour at a 0.5 mm bound takes 3·10^6.
inline constexpr std::size_t kMaxContourSamples = std::size_t(1) << 22;

/// The verifier's verdict on a simplification: both directions between
/// `input` and `result`, and, given `contours`, their points every
/// `contourStepMm` (use a fraction of the bound) to the result.
struct SimplificationDistance {
    TwoSidedDistance surfaces;
    SampledDistance contours;  // samples == 0 without contours
    double maxMm() const { return std::max(surfaces.maxMm(), contours.maxMm); }
};
SimplificationDistance verifySimplification(const TriangleSoup& input, const TriangleSoup& result,
                                            const Roi* contours, double contourStepMm,
                                            std::size_t samplesPerSurface);

}  // namespace dfrecon
