#pragma once
// Distances to a shape's true surface for measuring reconstructions. Exact
// distances are used as they are; for a shape whose signedDistance is only a
// bound (a smooth union: |value| <= true distance), the distance is measured
// against a dense set of points exactly on its surface, refined to the foot
// point, so both directions of a benchmark measure the same surface.
#include <cstddef>
#include <unordered_map>
#include <vector>

#include "shapes/AnalyticShapes.hpp"

namespace dfrecon {

class SurfaceReference {
  public:
    /// For an inexact shape, `samples` points of sampleSurface (seeded) are
    /// put in a grid of `cellMm` cells; nothing is built for exact shapes.
    explicit SurfaceReference(const AnalyticShape& shape, std::size_t samples = 100000,
                              double cellMm = 1.0);

    /// Unsigned distance from p to the surface. Exact shapes:
    /// |signedDistance(p)|. Others: |p - x| for the foot point x reached from
    /// the nearest dense sample by Hartmann's iteration (project p on the
    /// tangent plane at x, back onto the zero set along the gradient, until x
    /// stops moving): a point of the surface, so never below the true
    /// distance, and equal to it wherever the nearest sample lies in the
    /// true foot point's basin (the samples are ~0.2 mm apart; surface
    /// curvature radii are millimetres). Never more than the nearest sample's
    /// distance.
    double distance(Vec3 p) const;

    /// The surface point whose distance distance() returns (inexact shapes
    /// only; p itself for exact ones).
    Vec3 nearestPoint(Vec3 p) const;

    /// Whether distance() is signedDistance itself.
    bool exact() const { return shape_.distanceIsExact(); }

  private:
    Vec3 project(Vec3 p) const;
    Vec3 gradient(Vec3 p) const;
    std::size_t nearestSample(Vec3 p) const;
    long long key(long long i, long long j, long long k) const;

    const AnalyticShape& shape_;
    double cell_;
    std::vector<Vec3> samples_;
    std::unordered_map<long long, std::vector<std::size_t>> grid_;
    long long lo_[3] = {0, 0, 0}, hi_[3] = {0, 0, 0};
};

}  // namespace dfrecon
