#pragma once
// Two delineations of one structure compared plane by plane, the way
// planning systems and contouring studies do it on contours: the volumes,
// the overlap (exact polygon Booleans on each plane × the plane's
// thickness) and the added path length (the length of the test contours
// that lies farther than a tolerance from the reference contours on the
// same plane: what an editor would have to redraw; Vaassen et al. 2020).
// Only for two contour inputs whose planes are the same ones.
#include <cstddef>
#include <string>

#include "contours/ContourSet.hpp"

namespace dfrecon {

struct PlaneComparisonOptions {
    /// Added path length's tolerance, mm: test contour within this distance
    /// of a reference contour on its plane counts as kept.
    double toleranceMm = 1;
    /// Planes of the two inputs this close are one plane (RTSTRUCT z values
    /// are written as decimal text, and rounding makes them differ).
    double planeMatchMm = 1e-3;
};

struct PlaneComparison {
    /// Whether the two lie on the same planes (parallel, and no plane of
    /// one between two planes of the other, though either may have planes
    /// the other lacks). When false, `whyNot` says why and nothing else is
    /// set.
    bool samePlanes = false;
    std::string whyNot;
    /// The planes of either, after matching.
    std::size_t planes = 0;
    /// Σ area × thickness over the planes of either: the planning system's
    /// volume; each plane's thickness by planeThicknessesMm over the planes
    /// of both, so that all three volumes weigh a plane alike, in runs that
    /// end where both ROIs leave planes empty (contours/PlaneGaps; a plane
    /// alone in its run stands for the image spacing), as contourVolumeMm3
    /// counts each ROI.
    double volumeAMm3 = 0, volumeBMm3 = 0, intersectionMm3 = 0;
    /// Total contour length of each, mm.
    double pathLengthAMm = 0, pathLengthBMm = 0;
    /// The length of B's contours farther than toleranceMm from A's
    /// contours on their plane (all of a contour on a plane where A has
    /// none): B is the test, A the reference. Exact up to rounding.
    double addedPathLengthMm = 0;
    /// The same with A as the test and B the reference.
    double addedPathLengthAMm = 0;
    double toleranceMm = 1;
    double unionMm3() const { return volumeAMm3 + volumeBMm3 - intersectionMm3; }
    /// 2|A ∩ B| / (|A| + |B|); 1 for two empty structures.
    double dice() const;
    /// |A ∩ B| / |A ∪ B|; 1 for two empty structures.
    double jaccard() const;
};

/// The per-plane comparison of `a` (the reference) and `b` (the test):
/// valid contours as the readers leave them (nested, not crossing), in
/// frames with the same plane normal up to sign (b is re-expressed in a's).
/// Areas of A ∩ B come from the exclusive or of both planes' contours
/// (geometry/PolygonXor, exact arithmetic): |A ∩ B| = (|A| + |B| − |A ⊕ B|)
/// / 2. Work per plane: O((n + k) log n) for n points and k crossings of
/// A's and B's contours, and O(n_B · m) for the added path length, m the A
/// segments whose boxes come within the tolerance of a B segment.
/// Throws TooManyCrossings (geometry/PolygonXor) for a plane where the two
/// cross more than kMaxPlaneCrossings times.
PlaneComparison comparePlanes(const Roi& a, const Roi& b, const PlaneComparisonOptions& options);

/// Most crossing points (with contours) of A's and B's contours on one
/// plane: the bound xorRegions holds its memory to (about 2 kB a crossing).
inline constexpr std::size_t kMaxPlaneCrossings = 200'000;

/// The length of `test`'s edges farther than `toleranceMm` from every edge
/// of `reference` (both closed polygons of one plane), exactly up to
/// rounding: along an edge, the points within the tolerance of a segment
/// form one interval (the distance to a segment is convex), found in
/// closed form and merged. O(n · m) for n test edges and m reference edges
/// near each.
double lengthOutsideTolerance(const std::vector<Polygon>& test,
                              const std::vector<Polygon>& reference, double toleranceMm);

}  // namespace dfrecon
