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
#include <vector>

#include "recon/SurfaceBuilder.hpp"

namespace dfrecon {

/// Contours of a layer taking part in a closing, by index.
struct LayerPart {
    const Layer* layer = nullptr;
    std::vector<std::uint32_t> contours;
};

/// Is the outermost contour (the largest by area) of `a` and `b` together a
/// hole: a cavity's own end, below the recursion's top level or where a
/// cavity ends? The fields of such parts alone are negative in the empty
/// space inside the holes (the sign comes from the winding number), so what
/// follows the negative region runs against the contours' orientation.
/// Parts of whole slices never are. O(points).
bool outermostIsHole(const LayerPart& a, const LayerPart& b = {});

/// Adds the walls and lid described above at height `middleZMm` (strictly
/// between the two layers' planes; either part may be empty). Every edge of
/// the parts' contours gets exactly one wall triangle fan, so the piece
/// joins watertight to whatever lies beyond those contours. The closing is
/// checked with its points rounded to float (shifted lids tried in turn,
/// see the .cpp); true when it holds, and then its triangles are one clean
/// group of the builder (SurfaceBuilder::markSearchedTogetherSince), so no
/// later check searches their pairs again. O(T log T) for its T triangles.
bool closeByPrisms(SurfaceBuilder& builder, const LayerPart& lower, const LayerPart& upper,
                   double middleZMm);

}  // namespace dfrecon
