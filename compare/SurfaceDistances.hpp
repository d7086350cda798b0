#pragma once
// Distances between two surfaces as contouring studies report them —
// Hausdorff, 95th percentile Hausdorff (HD95) and mean surface distance —
// from every point of each surface, not from voxels: each triangle is
// sampled on a barycentric lattice no coarser than `spacingMm`, each sample
// gets the exact distance to the other surface (closest point over a BVH),
// and statistics are weighted by the area each sample stands for. Any point
// of a triangle lies within its lattice cell's longest edge (<= spacingMm)
// of a sample, and distances are 1-Lipschitz, so every reported figure is
// within spacingMm of the exact one over the surfaces.
#include <cstddef>

#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

struct DirectedDistances {
    double maxMm = 0;   // Hausdorff from this surface to the other
    double p95Mm = 0;   // area-weighted 95th percentile
    double meanMm = 0;  // area-weighted mean
    /// The area of this surface within the tolerance of the other (by the
    /// samples: each stands for its lattice cell).
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

/// Distances between `a` and `b` (any triangle soups; closed or not).
/// Throws std::invalid_argument for an empty surface or spacingMm <= 0.
/// Work: O(S log T) for S = area / spacingMm² samples, S at most
/// kMaxDistanceSamples (the spacing grows to keep it so); memory O(S + T).
SurfaceDistances surfaceDistances(const TriangleSoup& a, const TriangleSoup& b, double spacingMm,
                                  double toleranceMm = 1);

}  // namespace dfrecon
