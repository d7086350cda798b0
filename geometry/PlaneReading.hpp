#pragma once
// How the contours of one plane are read, as planning systems and voxel
// tools read them. Exports hold what a drawing tool leaves behind: points
// repeated, a line drawn out and back (a fold), a contour stored twice, a
// contour with no area, a loop that crosses itself or another. Each is
// resolved here into the simple, non-crossing contours a Slice holds, under
// the even-odd rule (DICOM's reading of contours on one plane, and how
// rasterisers fill them), with every change counted for the report. Points
// on the resulting boundary are kept exactly as given.
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "geometry/Polygon.hpp"

namespace dfrecon {

/// What reading changed, summed over the planes of an ROI.
struct PlaneReadingCounts {
    std::size_t repeatedPoints = 0;     // a point equal to the one before it (or the closing point)
    std::size_t foldPoints = 0;         // tips of zero-width spikes: out along a line and back
    std::size_t zeroAreaContours = 0;   // contours left with no area (all on one line): dropped
    std::size_t duplicateContours = 0;  // repeating another contour of the plane point for point
    std::size_t keyholeCuts = 0;        // a contour touching itself, split into loops
    std::size_t resolvedContours = 0;  // crossed itself or another: replaced by the even-odd region
    std::size_t planesResolved = 0;    // planes where contours were replaced so

    PlaneReadingCounts& operator+=(const PlaneReadingCounts& other);
    /// Whether anything but keyhole cuts (a hole convention, not a defect)
    /// and repeated points (harmless) changed the drawing.
    bool changedShape() const;
    /// "2 duplicate contours dropped, 1 self-crossing contour resolved by
    /// the even-odd rule, ..."; empty when nothing changed.
    std::string summary() const;
};

/// A contour of the result that came from a filled group rather than one
/// input contour.
inline constexpr std::size_t kResolvedContour = std::numeric_limits<std::size_t>::max();

struct PlaneReading {
    /// Simple contours, no two crossing or overlapping (they may touch at
    /// points), in no particular orientation (Slice's normaliseOrientation
    /// orients them).
    std::vector<Polygon> contours;
    /// The input contour each came from, or kResolvedContour.
    std::vector<std::size_t> sourceOf;
    PlaneReadingCounts counts;
    /// Contours and crossings the even-odd fills combined (xorRegions'
    /// work), for a caller that bounds a whole file's.
    std::size_t work = 0;
};

/// Reads one plane's contours: repeats and fold tips dropped, contours of
/// no area and exact duplicates (the same points in the same cyclic order,
/// either way round) dropped, self-touching contours split at the touch
/// (keyholes), and each group of contours whose boxes overlap and that
/// crosses or overlaps itself replaced by its even-odd region (xorRegions).
/// Contours in no such group keep their points exactly. Throws
/// TooManyCrossings when a group needs more than `maxWork` contours and
/// crossings combined. A plane whose layout is too complex to search
/// (ContourDefect::TooComplex) is returned as cleaned, for the caller's
/// validation to report. O(n log n) typical for n points; the fill's cost
/// where a group needs it.
PlaneReading readPlaneContours(std::vector<Polygon> contours, std::size_t maxWork);

}  // namespace dfrecon
