#pragma once
// The region that closed contours bound under the even-odd rule (DICOM's
// CLOSEDPLANAR_XOR; how planning systems and voxel tools fill contours that
// cross themselves or each other, fold back or share edges, as mask
// converters write holes that reach the image border).
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

/// The region `contours` bound under the even-odd rule: the points a ray
/// from them leaves through an odd number of contour segments. The contours
/// may have any shape: cross themselves or one another, fold back along a
/// line, share or overlap edges, touch; a segment drawn twice cancels (a
/// keyhole's channel, a fold), as does a contour drawn twice. Returned as
/// simple boundaries: outer boundaries counter-clockwise, holes clockwise,
/// no two crossing (they may touch at points). Every point of the contours
/// that lies on the result's boundary is a point of it, exactly as given;
/// crossing points are rounded to double. Exact predicates and
/// constructions (a CGAL arrangement of the segments, overlapping pieces
/// counted per segment), so shared edges cancel exactly. O((n + k) log n)
/// for n points and k crossings; about 2 kB and 0.1 ms per crossing. The
/// contours plus the pairs of segments that meet (countContourContacts,
/// ContactsCounted::All) must not exceed `maxWork`, or TooManyCrossings is
/// thrown first (150 contours all crossing one another took 2.5 GB). CGAL
/// runs on a thread with a 256 MB stack. `work`, when given, receives the
/// contours plus crossings combined.
std::vector<Polygon> xorRegions(const std::vector<Polygon>& contours, std::size_t maxWork,
                                std::size_t* work = nullptr);

}  // namespace dfrecon
