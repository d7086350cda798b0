#pragma once
// The region that closed contours bound under the even-odd rule (DICOM's
// CLOSEDPLANAR_XOR, and the reading of CLOSED_PLANAR contours that share
// edges, as mask converters write holes that reach the image border).
#include <cstddef>
#include <stdexcept>
#include <vector>

#include "geometry/Polygon.hpp"

namespace dfrecon {

/// Thrown by xorRegions, before any work, when the contours are more than
/// it may combine (what() says how many contours, crossings and the limit).
class TooManyCrossings : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

/// The exclusive-or of the regions of `contours` (each simple; they may
/// cross, overlap or share edges), as the boundaries of the result: outer
/// boundaries counter-clockwise, holes clockwise, no two crossing. Exact
/// arithmetic (CGAL's Boolean set operations), so shared edges cancel
/// exactly; crossing points are rounded to double. O((n + k) log n) for n
/// points and k crossings. CGAL's arrangement takes about 2 kB and 0.1 ms
/// per crossing and is scanned recursively, one call per face: the contours
/// plus the pairs of segments that meet (countContourContacts) must not
/// exceed `maxWork`, or TooManyCrossings is thrown first (150 contours all
/// crossing one another took 2.5 GB, then overflowed the stack). CGAL runs
/// on a thread with a 256 MB stack. `work`, when given, receives the
/// contours plus crossings combined.
std::vector<Polygon> xorRegions(const std::vector<Polygon>& contours, std::size_t maxWork,
                                std::size_t* work = nullptr);

}  // namespace dfrecon
