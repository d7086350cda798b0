#pragma once
// Geometric validity of the contours of one slice: each contour a simple
// polygon, no two contours crossing or overlapping. Contours of one slice may
// touch at isolated points (planning systems draw such outlines).
#include <cstddef>
#include <optional>
#include <vector>

#include "geometry/Polygon.hpp"

namespace dfrecon {

struct ContourDefect {
    enum class Kind {
        SelfIntersection,  // two segments of one contour meet where they should not
        Crossing,          // segments of two contours cross or overlap
        TooComplex,        // over the pair or grid-entry budget (hostile input)
    };
    Kind kind;
    // Segment k joins point k and point k+1 (mod n) of its contour.
    std::size_t contourA = 0, segmentA = 0, contourB = 0, segmentB = 0;
    SegmentContact contact = SegmentContact::Cross;
};

/// Upper bound on segment pairs examined, so that a pathological slice gives
/// an error instead of running for hours (grid entries are capped at
/// 16 per segment plus 10⁶ likewise, bounding memory). Real slices use a tiny
/// fraction of both.
inline constexpr std::size_t kDefaultPairBudget = 400'000'000;

/// The first defect found, or nothing if the slice is valid. Segments are
/// binned into a uniform grid (cells walked along each segment), and only
/// segments sharing a cell are compared: O(n + pairs in shared cells),
/// about O(n) for contours sampled finer than the grid.
std::optional<ContourDefect> findContourDefect(const std::vector<Polygon>& contours,
                                               std::size_t pairBudget = kDefaultPairBudget);

/// Which pairs of segments countContourContacts counts.
enum class ContactsCounted {
    BetweenContours,  // segments of different contours only
    All,              // also two segments of one contour that are not neighbours,
                      // and neighbours that fold back onto each other
};

/// How many pairs of segments meet (cross, touch or overlap), counted until
/// more than `stopAfter` are found (then stopAfter + 1 is returned) or
/// `pairBudget` pairs have been examined (then SIZE_MAX): the crossings a
/// Boolean operation on the contours has to build. Same grid as
/// findContourDefect; memory O(n + stopAfter).
std::size_t countContourContacts(const std::vector<Polygon>& contours, std::size_t stopAfter,
                                 std::size_t pairBudget = kDefaultPairBudget,
                                 ContactsCounted counted = ContactsCounted::BetweenContours);

/// A point where two different contours of one slice touch (share one point
/// without crossing); segment k joins point k and point k+1 of its contour.
struct ContourTouch {
    std::size_t contourA = 0, segmentA = 0, contourB = 0, segmentB = 0;
    Point2 at;
};

/// Every touch between two different contours, found as findContourDefect
/// finds contacts (a pair of segments may report the same point as another
/// pair). Crossings are not listed: findContourDefect reports those. Stops
/// early, with what it found so far, past `pairBudget` segment pairs.
std::vector<ContourTouch> findContourTouches(const std::vector<Polygon>& contours,
                                             std::size_t pairBudget = kDefaultPairBudget);

}  // namespace dfrecon
