#pragma once
// Proximity queries between pairs of objects (paper §6.3) on top of
// pairwise distance maps: separation distance, closest point pair,
// collision, and how deep one object reaches into another — each with its
// discretisation bound (paper §5): the maps are exact at their samples and
// every surface point is within the atlas's sampling bound of a sample, so
// a sampled minimum overestimates the true one by at most that bound.
#include <cstddef>
#include <vector>

#include "sdm/SurfaceDistanceMaps.hpp"

namespace dfrecon {

struct PairProximity {
    std::size_t first = 0, second = 0;
    /// Sampled separation: the true distance between the surfaces lies in
    /// [separationMm - boundMm, separationMm]. 0 when the surfaces meet.
    double separationMm = 0;
    double boundMm = 0;
    Vec3 pointOnFirst, pointOnSecond;  // the sampled closest pair
    /// Exact: some triangle of one crosses or touches a triangle of the
    /// other (triangle–triangle tests over a hierarchy, not sampled).
    bool surfacesIntersect = false;
    /// One lies wholly inside the other (closed objects; decided by the
    /// sign at the samples when the surfaces do not meet).
    bool firstInsideSecond = false, secondInsideFirst = false;
    /// Penetration estimate: the largest depth of a sample of either
    /// object inside the other (0 when none is inside); the deepest
    /// point's true depth is at most depthBoundMm more.
    double deepestPointMm = 0;
    double depthBoundMm = 0;

    bool colliding() const { return surfacesIntersect || firstInsideSecond || secondInsideFirst; }
};

/// Every unordered pair of the scene's objects, from pairwise maps of their
/// samples (two closest-primitive calls per pair: first against second and
/// second against first). O(pairs · samples · log T).
std::vector<PairProximity> proximityQueries(const SurfaceScene& scene,
                                            const std::vector<ObjectSamples>& samples,
                                            const ClosestPrimitivesFn& closest);

/// Do the surfaces of objects a and b share a point? Exact up to rounding;
/// visits only triangle pairs whose boxes overlap.
bool surfacesIntersect(const TriangleSoup& a, const TriangleSoup& b);

}  // namespace dfrecon
