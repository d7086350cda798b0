#pragma once
// A slab between two runs of repeated contours. Where a plane repeats the
// contours of the plane below it (a contour copied to the next slice, or the
// same pixels traced again) the structure is a prism there, and the smooth
// interpolant goes flat in z (recon/SliceInterpolant). A slab whose lower
// plane repeats the plane below and whose upper plane repeats the plane
// above, while the two differ, is then a step between two prisms: the data
// says nothing of a slope, and a slope drawn through it cuts across the
// step's flat face (a stem splitting into two branches, a bone's shaft
// meeting its head). Such a slab is closed as a step at its middle height
// (recon/PrismClosing), as the planning system's stack of slabs counts it:
// its volume is each contour's area times half the spacing on either side.
#include <cstddef>
#include <deque>

#include "recon/SurfaceBuilder.hpp"

namespace dfrecon {

/// Do `a` and `b` hold the same contours: as many, each with a contour of
/// the other holding the same points in the same cyclic order (any start),
/// each within `toleranceMm` in the plane? O(c²) for c contours a plane (a
/// point count and bounds compared per pair), plus O(points) per pair that
/// passes.
bool sameContours(const Layer& a, const Layer& b, double toleranceMm);

/// Is the slab between layers `s` and `s + 1` a step: layer s repeats layer
/// s - 1, layer s + 1 repeats layer s + 2, and the two differ? False at the
/// ends of the stack (a repeat needs a plane beyond). Cost: sameContours on
/// three pairs of layers.
bool isStepSlab(const std::deque<Layer>& layers, std::size_t s);

}  // namespace dfrecon
