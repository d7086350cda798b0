#pragma once
// `--repair-contours`: a contour that crosses itself (a figure eight, a loop
// drawn over its own start) has no inside under the nonzero rule that
// simple contours share, so it is an error by default. Under the even-odd
// rule — DICOM's CLOSEDPLANAR_XOR, and what most viewers fill — it bounds a
// definite region: the points a ray leaves through an odd number of times.
// This resolves such a contour into simple contours bounding that region.
#include <cstddef>
#include <optional>
#include <vector>

#include "geometry/Polygon.hpp"

namespace dfrecon {

/// The simple loops `contour` falls into when it is cut at every point
/// where two of its segments cross: a figure eight gives its two lobes.
/// Parity of ray crossings adds up over the loops, so the even-odd region
/// of `contour` is exactly the exclusive or of the loops' regions
/// (xorRegions). Crossing points are rounded to double; loops of zero area
/// are dropped. Returns nothing when a cut leaves a loop that still touches
/// or overlaps itself (segments running along one another), or when more
/// than `maxCuts` cuts would be needed. A simple contour comes back as its
/// only loop. O(cuts · n) for n points.
std::optional<std::vector<Polygon>> splitAtSelfCrossings(const Polygon& contour,
                                                         std::size_t maxCuts);

/// The even-odd region of a self-crossing `contour` as simple contours
/// (outer counter-clockwise, holes clockwise; they may touch at points):
/// splitAtSelfCrossings, then the exclusive or of the loops (CGAL, exact),
/// bounded by `maxWork` as xorRegions is. Nothing when the contour cannot
/// be split, when the loops need more than `maxWork` contours and crossings
/// combined, or when its even-odd region is empty (a path drawn round
/// twice): every caller then keeps the contour and reports it as it would
/// without repair.
std::optional<std::vector<Polygon>> evenOddRegion(const Polygon& contour, std::size_t maxCuts,
                                                  std::size_t maxWork);

}  // namespace dfrecon
