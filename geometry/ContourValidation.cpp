#include "geometry/ContourValidation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_set>

namespace dfrecon {

namespace {

struct Segment {
    std::size_t contour, index;
    Point2 a, b;
};

// Uniform grid over the slice's bounding box, about one cell per segment.
struct Grid {
    Point2 origin;
    double cell = 1;
    int size = 1;  // cells per side

    int column(double x) const { return std::clamp(int((x - origin.x) / cell), 0, size - 1); }
    int row(double y) const { return std::clamp(int((y - origin.y) / cell), 0, size - 1); }
};

Grid makeGrid(const std::vector<Segment>& segments) {
    Box2 box;
    for (const Segment& s : segments) {
        box.add(s.a);
        box.add(s.b);
    }
    Grid grid;
    grid.size = std::clamp(int(std::ceil(std::sqrt(double(segments.size())))), 1, 4096);
    const double extent = std::max(box.max.x - box.min.x, box.max.y - box.min.y);
    grid.cell = extent > 0 ? extent / grid.size * (1 + 1e-9) : 1;
    grid.origin = box.min;
    return grid;
}

// Appends the cells that segment s passes through, column by column (with
// neighbours on cell borders included, so no contact can fall between cells).
template <class Visit>
void visitCells(const Grid& grid, const Segment& s, Visit&& visit) {
    Point2 a = s.a, b = s.b;
    if (a.x > b.x) std::swap(a, b);
    const int c0 = grid.column(a.x), c1 = grid.column(b.x);
    for (int c = c0; c <= c1; ++c) {
        const double x0 = std::max(a.x, grid.origin.x + c * grid.cell);
        const double x1 = std::min(b.x, grid.origin.x + (c + 1) * grid.cell);
        double y0 = a.y, y1 = b.y;
        if (b.x > a.x) {
            const double slope = (b.y - a.y) / (b.x - a.x);
            y0 = a.y + slope * (x0 - a.x);
            y1 = a.y + slope * (x1 - a.x);
        }
        const int r0 = grid.row(std::min(y0, y1)), r1 = grid.row(std::max(y0, y1));
        for (int r = r0; r <= r1; ++r)
            visit(std::size_t(r) * std::size_t(grid.size) + std::size_t(c));
    }
}

bool adjacent(const Segment& s, const Segment& t, std::size_t contourSize) {
    const std::size_t d = s.index > t.index ? s.index - t.index : t.index - s.index;
    return d == 1 || d == contourSize - 1;
}

// The two directions in which `contour` leaves point p, which lies on its
// segment `index` (at an end or inside).
std::array<Point2, 2> raysAt(const Polygon& contour, std::size_t index, Point2 p) {
    const std::size_t n = contour.size();
    const Point2 a = contour[index], b = contour[(index + 1) % n];
    if (p == a) return {contour[(index + n - 1) % n] - p, b - p};
    if (p == b) return {a - p, contour[(index + 2) % n] - p};
    return {a - p, b - p};
}

// Counter-clockwise angle from direction `from` to direction `to`, in [0, 2π).
double turn(Point2 from, Point2 to) {
    const double angle = std::atan2(cross(from, to), dot(from, to));
    return angle < 0 ? angle + 2 * M_PI : angle;
}

// Whether two contours that meet at the single point p pass through each
// other there: the other contour's two directions lie in different sectors
// of the plane that this contour's two directions bound. Touching contours
// stay on one side; crossing ones make the nesting ambiguous.
bool crossAtPoint(const Polygon& a, std::size_t segmentA, const Polygon& b, std::size_t segmentB,
                  Point2 p) {
    const std::array<Point2, 2> ra = raysAt(a, segmentA, p), rb = raysAt(b, segmentB, p);
    const double sector = turn(ra[0], ra[1]);
    const bool first = turn(ra[0], rb[0]) < sector, second = turn(ra[0], rb[1]) < sector;
    return first != second;
}

// The point two touching segments share: the end of one that lies on the
// other (nearest, as the distance of a point on a segment may round above 0).
Point2 touchPoint(const Segment& s, const Segment& t) {
    Point2 best = s.a;
    double bestDistance = INFINITY;
    for (const auto& [p, other] :
         {std::pair{s.a, &t}, std::pair{s.b, &t}, std::pair{t.a, &s}, std::pair{t.b, &s}}) {
        const double d = distanceToSegment(p, other->a, other->b);
        if (d < bestDistance) {
            best = p;
            bestDistance = d;
        }
    }
    return best;
}

// Calls visit(s, t, contact) for every pair of segments that meet
// (contact != None), until it returns true; returns false when the budget
// ran out first.
template <class Visit>
bool visitContacts(const std::vector<Segment>& segments, std::size_t pairBudget, Visit&& visit) {
    if (segments.size() < 2) return true;
    const Grid grid = makeGrid(segments);
    std::size_t work = 0;
    // (cell, segment) entries sorted by cell: each cell's segments contiguous.
    // Segments much longer than a cell visit many cells; the cap bounds
    // memory on layouts such as combs of long teeth.
    const std::size_t maxEntries = 16 * segments.size() + 1'000'000;
    std::vector<std::pair<std::size_t, std::uint32_t>> entries;
    for (std::size_t i = 0; i < segments.size(); ++i) {
        visitCells(grid, segments[i],
                   [&](std::size_t cell) { entries.emplace_back(cell, std::uint32_t(i)); });
        if (entries.size() > maxEntries) return false;
    }
    std::sort(entries.begin(), entries.end());
    for (std::size_t begin = 0; begin < entries.size();) {
        std::size_t end = begin;
        while (end < entries.size() && entries[end].first == entries[begin].first) ++end;
        for (std::size_t p = begin; p < end; ++p)
            for (std::size_t q = p + 1; q < end; ++q) {
                if (++work > pairBudget) return false;
                const Segment& s = segments[entries[p].second];
                const Segment& t = segments[entries[q].second];
                const SegmentContact contact = segmentContact(s.a, s.b, t.a, t.b);
                if (contact != SegmentContact::None && visit(s, t, contact)) return true;
            }
        begin = end;
    }
    return true;
}

std::vector<Segment> segmentsOf(const std::vector<Polygon>& contours) {
    std::vector<Segment> segments;
    for (std::size_t c = 0; c < contours.size(); ++c)
        for (std::size_t i = 0; i < contours[c].size(); ++i)
            segments.push_back({c, i, contours[c][i], contours[c][(i + 1) % contours[c].size()]});
    return segments;
}

}  // namespace

std::optional<ContourDefect> findContourDefect(const std::vector<Polygon>& contours,
                                               std::size_t pairBudget) {
    std::optional<ContourDefect> found;
    const bool complete = visitContacts(
        segmentsOf(contours), pairBudget,
        [&](const Segment& s, const Segment& t, SegmentContact contact) {
            ContourDefect defect{
                ContourDefect::Kind::Crossing, s.contour, s.index, t.contour, t.index, contact};
            if (s.contour == t.contour) {
                // Neighbours share a vertex; only folding back onto each other is wrong.
                if (adjacent(s, t, contours[s.contour].size()) &&
                    contact != SegmentContact::Overlap)
                    return false;
                defect.kind = ContourDefect::Kind::SelfIntersection;
                found = defect;
                return true;
            }
            // Contours may touch at isolated points, but not cross there.
            if (contact == SegmentContact::Touch) {
                if (!crossAtPoint(contours[s.contour], s.index, contours[t.contour], t.index,
                                  touchPoint(s, t)))
                    return false;
                defect.contact = SegmentContact::Cross;
            }
            found = defect;
            return true;
        });
    if (!complete) return ContourDefect{ContourDefect::Kind::TooComplex};
    return found;
}

std::size_t countContourContacts(const std::vector<Polygon>& contours, std::size_t stopAfter,
                                 std::size_t pairBudget, ContactsCounted counted) {
    // A pair sharing several cells is met once per cell: kept in a set, so
    // each counts once (the set holds at most stopAfter + 1 pairs).
    const std::vector<Segment> segments = segmentsOf(contours);
    std::unordered_set<std::uint64_t> pairs;
    const bool complete = visitContacts(
        segments, pairBudget, [&](const Segment& s, const Segment& t, SegmentContact contact) {
            if (s.contour == t.contour && (counted == ContactsCounted::BetweenContours ||
                                           (adjacent(s, t, contours[s.contour].size()) &&
                                            contact != SegmentContact::Overlap)))
                return false;
            std::uint64_t i = std::uint64_t(&s - segments.data()),
                          j = std::uint64_t(&t - segments.data());
            if (i > j) std::swap(i, j);
            pairs.insert(i << 32 | j);
            return pairs.size() > stopAfter;
        });
    return complete ? pairs.size() : SIZE_MAX;
}

std::vector<ContourTouch> findContourTouches(const std::vector<Polygon>& contours,
                                             std::size_t pairBudget) {
    std::vector<ContourTouch> touches;
    visitContacts(
        segmentsOf(contours), pairBudget,
        [&](const Segment& s, const Segment& t, SegmentContact contact) {
            if (s.contour != t.contour && contact == SegmentContact::Touch)
                touches.push_back({s.contour, s.index, t.contour, t.index, touchPoint(s, t)});
            return false;
        });
    return touches;
}

}  // namespace dfrecon
