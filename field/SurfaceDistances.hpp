#pragma once
// Distances between two surfaces as contouring studies report them —
// Hausdorff, 95th percentile Hausdorff (HD95), mean surface distance and
// surface Dice — from every point of each surface, not from voxels: each
// triangle is cut into cells (halving longest edges) until every cell's
// corners, and so all its points, lie within `spacingMm` of its centroid;
// each centroid gets the exact distance to the other surface, and
// statistics weigh it by its cell's area. Distances are 1-Lipschitz, so
// every reported figure is within spacingMm of the exact one over the
// surfaces.
#include <cstddef>

#include "cl/Runtime.hpp"
#include "geometry/TriangleBvh.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

struct DirectedDistances {
    double maxMm = 0;   // Hausdorff from this surface to the other
    double p95Mm = 0;   // area-weighted 95th percentile
    double meanMm = 0;  // area-weighted mean
    /// The area of this surface within the tolerance of the other (by the
    /// samples: each stands for its cell).
    double areaWithinToleranceMm2 = 0;
    std::size_t samples = 0;
};

/// Most samples on either surface (each 16 bytes while the percentiles are
/// found): where `spacingMm` would take more, the spacing is coarsened until
/// it does not, and reported as used.
inline constexpr std::size_t kMaxDistanceSamples = std::size_t(1) << 23;

struct SurfaceDistances {
    DirectedDistances aToB, bToA;
    /// The spacing used, the bound on every figure's error: the one asked
    /// for unless that took more than kMaxDistanceSamples samples.
    double spacingMm = 0;
    /// max of the two directed Hausdorff distances.
    double hausdorffMm() const;
    /// max of the two directed 95th percentiles (plastimatch's, Slicer's
    /// convention).
    double hd95Mm() const;
    /// Area-weighted mean over both surfaces together.
    double meanMm() const;
    double areaAMm2 = 0, areaBMm2 = 0;
    /// The 95th percentile of both directions' distances pooled, weighted
    /// by area (DeepMind's surface-distance and MONAI's convention), where
    /// hd95Mm() takes the larger of the two directions' own.
    double hd95PooledMm = 0;
    /// Surface Dice at toleranceMm (Nikolov et al. 2018): the area of each
    /// surface within the tolerance of the other, over both areas:
    /// (|A within τ of B| + |B within τ of A|) / (|A| + |B|). Each sample
    /// stands for its cell, so it lies between the exact values at τ ∓
    /// spacingMm.
    double toleranceMm = 1;
    double surfaceDice() const;
};

/// The spacing surfaceDistances samples `a` and `b` at when asked for
/// `spacingMm`: geometry/TriangleCells' cellSpacingWithinBudget with
/// kMaxDistanceSamples cells.
double distanceSpacingWithinBudget(const TriangleSoup& a, const TriangleSoup& b, double spacingMm);

/// Distances between `a` and `b` (any triangle soups; closed or not), on
/// the host: each sample's nearest point over a TriangleBvh. The reference
/// the device version is held to. Throws std::invalid_argument for an
/// empty surface or spacingMm <= 0. Work: O(S log T) for S = area /
/// spacingMm² samples, S at most kMaxDistanceSamples (the spacing grows to
/// keep it so); memory O(S + T).
SurfaceDistances surfaceDistances(const TriangleSoup& a, const TriangleSoup& b, double spacingMm,
                                  double toleranceMm = 1);

/// The same on the host over hierarchies the caller built (`bvhA` of `a`,
/// `bvhB` of `b`), at `spacingMm` as given: for callers that measure more
/// against the same surfaces (simplify's verifier) and keep their own
/// sample budget. Throws as above. Work: O(S log T).
SurfaceDistances surfaceDistances(const TriangleSoup& a, const TriangleBvh& bvhA,
                                  const TriangleSoup& b, const TriangleBvh& bvhB, double spacingMm,
                                  double toleranceMm = 1);

/// The same figures from the closest-primitive kernel
/// (field/ClosestPrimitives: each sampled triangle culls the other
/// surface's hierarchy once, each sample measures the few candidates left),
/// the samples sent in runs of 2^20. Equal to the host's up to rounding in
/// double precision; within 1e-6 of the surfaces' extent on a device
/// without fp64. Throws as the host version, and ocl::ClError on device
/// failure. Work as the host's, spread over the device; memory O(S + T).
SurfaceDistances surfaceDistances(ocl::Runtime& runtime, const TriangleSoup& a,
                                  const TriangleSoup& b, double spacingMm, double toleranceMm = 1);

}  // namespace dfrecon
