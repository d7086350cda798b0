#pragma once
// Keyhole contours: planning systems and converters (plastimatch among them)
// draw a hole as part of its outer contour, joined by a zero-width channel:
// the path runs in along the channel, around the hole, and back out over the
// same points. Split such a contour into its outer loop and its holes so the
// nesting rules of Slice apply.
#include <vector>

#include "geometry/Polygon.hpp"

namespace dfrecon {

struct KeyholeSplit {
    std::vector<Polygon> loops;  // simple loops, in no particular orientation
    std::size_t cuts = 0;        // how many times the contour touched itself
};

/// Splits `contour` wherever it revisits a point: vertices equal within
/// `toleranceMm`, or a vertex lying on another edge (a channel whose two
/// sides were sampled at different points). Each visit cuts the closed path
/// into two closed paths; loops of zero area (the channel's two sides) are
/// dropped. A contour that never touches itself comes back unchanged as
/// the only loop, with cuts = 0. Loops may still touch each other at single
/// points. O(n²) in the worst case for n points, O(n log n) typical.
KeyholeSplit splitKeyholes(const Polygon& contour, double toleranceMm = 1e-6);

}  // namespace dfrecon
