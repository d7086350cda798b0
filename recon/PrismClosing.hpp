#pragma once
// Closing what tracing cannot connect. Between a set of lower contours X and
// upper contours Y, the solid X×[zx, zm] ∪ Y×[zm, zy] is always a valid
// closed piece: vertical walls on X up to zm, on Y down to zm, and at zm a
// flat lid over the symmetric difference of X's and Y's regions (facing up
// where only X is solid, down where only Y is). With Y empty it is an end
// cap. The recursion of the reconstruction makes these pieces thin (a
// sixteenth of the slice spacing at the default depth), so what remains of
// a branching region costs a small step, never a hole.
#include <cstdint>
#include <functional>
#include <vector>

#include "recon/SurfaceBuilder.hpp"

namespace dfrecon {

/// Contours of a layer taking part in a closing, by index.
struct LayerPart {
    const Layer* layer = nullptr;
    std::vector<std::uint32_t> contours;
};

/// Adds the walls and lid described above at height `middleZMm` (strictly
/// between the two layers' planes; either part may be empty). Every edge of
/// the parts' contours gets exactly one wall triangle fan, so the piece
/// joins watertight to whatever lies beyond those contours.
void closeByPrisms(SurfaceBuilder& builder, const LayerPart& lower, const LayerPart& upper,
                   double middleZMm);

/// A rounded cap over the region of `part`'s contours: it starts at the
/// contours in their plane and rises (upward when `up`, else downward) to
/// `heightMm`, along a quarter circle that is vertical at the rim and flat
/// once `roundingMm` inside (a plateau; with roundingMm at least the region's
/// depth, a dome). `depthMm(p)` is the distance from p to the contours; the
/// cap's inner vertices sit at `interiorPoints`, which must lie inside the
/// region and off the contours. A height field over a planar triangulation,
/// so it cannot fold onto itself.
void roundedCap(SurfaceBuilder& builder, const LayerPart& part, bool up, double heightMm,
                double roundingMm, const std::vector<Point2>& interiorPoints,
                const std::function<double(Point2)>& depthMm);

}  // namespace dfrecon
