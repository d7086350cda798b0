#pragma once
// Marching squares on a plain image: the borders of the region where a
// sampled scalar is negative, as closed polygons in pixel-index coordinates.
// Lives in geometry so that readers (label volumes → contours) and recon (2D fields
// → intermediate contours) share one implementation.
#include <vector>

#include "geometry/Polygon.hpp"

namespace dfrecon {

/// Where the samples of an image lie: sample (i, j) at
/// (originMm.x + (i + indexOffset.x)·stepMm.x, originMm.y + (j + indexOffset.y)·stepMm.y).
/// The default puts sample (i, j) at the point (i, j) (pixel-index
/// coordinates). Steps must be positive, so orientation is kept.
struct SampleLattice {
    Point2 originMm{0, 0};
    Point2 stepMm{1, 1};
    Point2 indexOffset{0, 0};

    Point2 at(int i, int j) const {
        return {originMm.x + (i + indexOffset.x) * stepMm.x,
                originMm.y + (j + indexOffset.y) * stepMm.y};
    }
};

/// The borders of the region where `values` < 0. `values` is a row-major
/// image of `width` × `height` samples (x fastest) placed by `lattice`;
/// samples outside the image count as +1, so every border closes (pad the
/// image where the crossings at its edge matter). Crossings are placed by
/// linear interpolation along the lattice edges between neighbouring samples (0.5 − mask gives the
/// midpoints between inside and outside samples). Samples in [0,
/// `minPositive`) are raised to `minPositive` first, so no crossing falls
/// exactly on a sample and polygons stay simple.
///
/// Guarantees: every polygon is closed (last point ≠ first), simple, has at
/// least 3 points, and no two polygons cross; outer borders run
/// counter-clockwise and hole borders clockwise (Slice's convention). Saddle
/// cells join their negative corners only when the cell's mean is
/// negative. Throws std::invalid_argument when values.size() ≠ width ·
/// height, a size is negative or a step is not positive. O(width · height).
std::vector<Polygon> negativeRegionBorders(const std::vector<float>& values, int width, int height,
                                           const SampleLattice& lattice = {},
                                           float minPositive = 1e-6f);

}  // namespace dfrecon
