#include "geometry/PlaneReading.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <set>

#include "geometry/ContourValidation.hpp"
#include "geometry/KeyholeSplit.hpp"
#include "geometry/PolygonXor.hpp"

namespace dfrecon {

PlaneReadingCounts& PlaneReadingCounts::operator+=(const PlaneReadingCounts& other) {
    repeatedPoints += other.repeatedPoints;
    foldPoints += other.foldPoints;
    zeroAreaContours += other.zeroAreaContours;
    duplicateContours += other.duplicateContours;
    keyholeCuts += other.keyholeCuts;
    resolvedContours += other.resolvedContours;
    planesResolved += other.planesResolved;
    return *this;
}

bool PlaneReadingCounts::changedShape() const {
    return foldPoints + zeroAreaContours + duplicateContours + resolvedContours > 0;
}

std::string PlaneReadingCounts::summary() const {
    std::string out;
    auto add = [&](std::size_t count, const char* one, const char* many) {
        if (count == 0) return;
        out += (out.empty() ? "" : ", ") + std::to_string(count) + " " + (count == 1 ? one : many);
    };
    add(repeatedPoints, "repeated point dropped", "repeated points dropped");
    add(foldPoints, "fold (a line drawn out and back) removed",
        "fold points (lines drawn out and back) removed");
    add(zeroAreaContours, "contour of no area dropped", "contours of no area dropped");
    add(duplicateContours, "duplicate contour dropped", "duplicate contours dropped");
    add(resolvedContours, "crossing contour replaced by its even-odd region",
        "crossing contours replaced by their even-odd region");
    if (planesResolved > 0)
        out += " (on " + std::to_string(planesResolved) +
               (planesResolved == 1 ? " plane)" : " planes)");
    return out;
}

namespace {

// Drops consecutive repeats and a closing point equal to the first.
std::size_t dropRepeats(Polygon& contour) {
    const std::size_t before = contour.size();
    contour.erase(std::unique(contour.begin(), contour.end()), contour.end());
    while (contour.size() > 1 && contour.back() == contour.front()) contour.pop_back();
    return before - contour.size();
}

// Is `tip` the end of a spike: the path comes in along a line and leaves
// back along it (its two neighbours on one ray from it)?
bool isSpikeTip(Point2 before, Point2 tip, Point2 after) {
    const Point2 u = before - tip, v = after - tip;
    return cross(u, v) == 0 && dot(u, v) > 0;
}

// Removes the tips of zero-width spikes until none is left: each removal
// takes away a piece of zero area, so the region the contour bounds is the
// same. A spike drawn over several points folds up one tip at a time
// (a stack, so each point is looked at a bounded number of times).
std::size_t dropFolds(Polygon& contour) {
    std::size_t removed = 0;
    bool again = true;
    while (again && contour.size() >= 3) {
        again = false;
        Polygon kept;
        kept.reserve(contour.size());
        for (const Point2 p : contour) {
            kept.push_back(p);
            // Fold the tail back while its last-but-one point is a tip.
            while (kept.size() >= 3 &&
                   isSpikeTip(kept[kept.size() - 3], kept[kept.size() - 2], kept.back())) {
                kept.erase(kept.end() - 2);
                ++removed;
                if (kept.size() >= 2 && kept.back() == kept[kept.size() - 2]) kept.pop_back();
            }
        }
        // The seam (last, first, second) is looked at in the next pass, with
        // the polygon rotated so the seam is inside.
        const std::size_t n = kept.size();
        if (n >= 3 && (isSpikeTip(kept[n - 2], kept[n - 1], kept[0]) ||
                       isSpikeTip(kept[n - 1], kept[0], kept[1]))) {
            std::rotate(kept.begin(), kept.begin() + std::ptrdiff_t(n / 2), kept.end());
            again = true;
        }
        again = again || kept.size() != contour.size();
        contour = std::move(kept);
        dropRepeats(contour);
    }
    return removed;
}

// A contour's points starting at its least point, running the way whose
// second point is the lesser: equal for two contours exactly when they are
// the same closed path.
Polygon canonical(const Polygon& contour) {
    auto less = [](Point2 a, Point2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); };
    const std::size_t n = contour.size();
    const std::size_t first =
        std::size_t(std::min_element(contour.begin(), contour.end(), less) - contour.begin());
    const bool forward = !less(contour[(first + n - 1) % n], contour[(first + 1) % n]);
    Polygon out;
    out.reserve(n);
    for (std::size_t k = 0; k < n; ++k)
        out.push_back(contour[forward ? (first + k) % n : (first + n - k) % n]);
    return out;
}

// Contours whose bounding boxes overlap, joined (union-find over the box
// pairs, O(c²) box tests for c contours).
std::vector<std::vector<std::size_t>> overlappingGroups(const std::vector<Polygon>& contours) {
    const std::size_t n = contours.size();
    std::vector<Box2> boxes;
    for (const Polygon& c : contours) boxes.push_back(boundingBox(c));
    std::vector<std::size_t> parent(n);
    std::iota(parent.begin(), parent.end(), std::size_t(0));
    auto root = [&](std::size_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
            if (boxes[i].min.x <= boxes[j].max.x && boxes[j].min.x <= boxes[i].max.x &&
                boxes[i].min.y <= boxes[j].max.y && boxes[j].min.y <= boxes[i].max.y)
                parent[root(i)] = root(j);
    std::map<std::size_t, std::vector<std::size_t>> members;
    for (std::size_t i = 0; i < n; ++i) members[root(i)].push_back(i);
    std::vector<std::vector<std::size_t>> groups;
    for (auto& [rootIndex, indices] : members) groups.push_back(std::move(indices));
    return groups;
}

// A defect that is not one: contours of a plane may touch at points.
bool needsFill(const std::optional<ContourDefect>& defect) {
    return defect && defect->kind != ContourDefect::Kind::TooComplex &&
           (defect->kind == ContourDefect::Kind::Crossing ||
            defect->contact != SegmentContact::Touch);
}

}  // namespace

PlaneReading readPlaneContours(std::vector<Polygon> contours, std::size_t maxWork) {
    PlaneReading out;
    PlaneReadingCounts& counts = out.counts;
    // Each contour on its own: repeats, folds, no area, keyholes.
    std::vector<Polygon> loops;
    std::vector<std::size_t> sources;
    std::set<Polygon, bool (*)(const Polygon&, const Polygon&)> seen(
        [](const Polygon& a, const Polygon& b) {
            return std::lexicographical_compare(
                a.begin(), a.end(), b.begin(), b.end(),
                [](Point2 p, Point2 q) { return p.x < q.x || (p.x == q.x && p.y < q.y); });
        });
    for (std::size_t i = 0; i < contours.size(); ++i) {
        Polygon& contour = contours[i];
        counts.repeatedPoints += dropRepeats(contour);
        // A contour all on one line has no area to fold up.
        if (contour.size() >= 3 && !allCollinear(contour)) counts.foldPoints += dropFolds(contour);
        if (contour.size() < 3 || allCollinear(contour)) {
            ++counts.zeroAreaContours;
            continue;
        }
        if (!seen.insert(canonical(contour)).second) {
            ++counts.duplicateContours;
            continue;
        }
        // A contour that touches itself or runs back along itself is a
        // keyhole (a hole joined to its outline by a channel drawn in and
        // out, as mask converters write them) or a pinch: split there, which
        // keeps every point; one that crosses itself is left whole for the
        // fill, and so is whatever the split leaves crossing.
        const std::optional<ContourDefect> self = findContourDefect({contour});
        if (self && self->kind == ContourDefect::Kind::SelfIntersection &&
            self->contact != SegmentContact::Cross) {
            KeyholeSplit split = splitKeyholes(contour);
            counts.keyholeCuts += split.cuts;
            for (Polygon& loop : split.loops) {
                loops.push_back(std::move(loop));
                sources.push_back(i);
            }
            continue;
        }
        loops.push_back(std::move(contour));
        sources.push_back(i);
    }
    // The plane as a whole: groups that cross are filled by the even-odd rule.
    if (!needsFill(findContourDefect(loops))) {
        out.contours = std::move(loops);
        out.sourceOf = std::move(sources);
        return out;
    }
    std::size_t workLeft = maxWork;
    for (const std::vector<std::size_t>& group : overlappingGroups(loops)) {
        std::vector<Polygon> members;
        for (std::size_t i : group) members.push_back(std::move(loops[i]));
        if (!needsFill(findContourDefect(members))) {
            for (std::size_t k = 0; k < group.size(); ++k) {
                out.contours.push_back(std::move(members[k]));
                out.sourceOf.push_back(sources[group[k]]);
            }
            continue;
        }
        std::size_t work = 0;
        std::vector<Polygon> region = xorRegions(members, workLeft, &work);
        workLeft -= std::min(workLeft, work);
        out.work += work;
        counts.resolvedContours += members.size();
        for (Polygon& loop : region) {
            out.contours.push_back(std::move(loop));
            out.sourceOf.push_back(kResolvedContour);
        }
    }
    ++counts.planesResolved;
    return out;
}

}  // namespace dfrecon
