#include "recon/RingCoarsening.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <stdexcept>

#include "geometry/SurfaceMeasures.hpp"

namespace dfrecon {

namespace {

// Middles of rungs between the same two levels share their z (halves of
// the same sums; as floats, within rounding where an oblique stack's plane
// frame is written in patient space); refinement counts this as flat too.
constexpr double kSameRingMm = 1e-6;
// A collapse may turn a triangle by at most this (cos 45 degrees): beyond,
// the band folds where the curve across it turns.
constexpr double kMinNormalCosine = 0.7071;
constexpr std::uint32_t kNoCollapse = UINT32_MAX;
// Undo rounds before a pass is given up whole.
constexpr int kUndoRounds = 4;

Vec3 normalOf(const Vec3& a, const Vec3& b, const Vec3& c) {
    return cross(b - a, c - a);
}

/// `check` (a valid solid's) after `collapses` collapses under the link
/// condition: each takes one vertex, three edges and two triangles and
/// keeps the components, the Euler characteristic and the genus; volume and
/// area are measured again. A whole check would count the same (the
/// coarsening test compares them) at O(T log T), where this is O(T).
void updateReport(MeshCheckReport& check, const TriangleSoup& soup, std::size_t collapses) {
    if (check.vertices < collapses || check.triangles != soup.triangles.size() + 2 * collapses)
        throw std::logic_error(
            "coarsenMiddleRings: the collapses do not add up (a defect of "
            "dfrecon; please report it with the input)");
    check.vertices -= collapses;
    check.edges -= 3 * collapses;
    check.triangles = soup.triangles.size();
    const SurfaceMeasures measures = measureSurface(soup);
    check.volumeMm3 = measures.volumeMm3;
    check.areaMm2 = measures.areaMm2;
}

/// One pass of collapses and what it takes to undo them.
class RingCoarseningPass {
  public:
    /// What a merged triangle is measured against.
    struct Judge {
        const SliceInterpolant& field;
        const RingCoarseningOptions& options;
        // How far vertex v's zero set is moved outward at height z, mm.
        const std::function<double(std::size_t, double)>& bulgeMm;
    };

    RingCoarseningPass(MarkedTriangles surface, std::size_t firstMade, const Judge& judge);

    /// Collapses what it can; returns the ids of the triangles changed
    /// (the triangles are renumbered: the two at each collapsed edge go).
    std::vector<std::size_t> collapse();
    /// Undoes every collapse one of whose triangles is in `defective`;
    /// returns the ids of the triangles it put back (changed ones, and the
    /// two removed ones appended at the end), empty when none was undone.
    std::vector<std::size_t> undo(const std::vector<std::size_t>& defective);
    /// Every collapse still made, undone; the ids as undo's.
    std::vector<std::size_t> undoAll();
    /// Triangles of every collapse still made (changed ones).
    std::vector<std::size_t> liveTriangles() const;
    std::size_t liveCollapses() const;

  private:
    struct Collapse {
        std::uint32_t from, into;          // v went into w
        std::vector<std::size_t> changed;  // triangle ids (current numbering)
        std::array<std::array<std::uint32_t, 3>, 2> removed;
        std::array<std::uint32_t, 2> removedPieces;
        bool live = true;
    };
    bool free(std::uint32_t v) const;
    std::vector<std::uint32_t> neighbours(std::uint32_t v) const;
    bool follows(const Vec3& p, std::uint32_t v) const;
    bool tryCollapse(std::uint32_t v, std::uint32_t w, const std::vector<std::uint32_t>& nv,
                     std::vector<bool>& gone);
    std::vector<std::size_t> undoWhere(const std::vector<bool>& which);

    MarkedTriangles surface_;
    std::size_t first_;
    Judge judge_;
    std::vector<std::uint32_t> fanStart_, fan_;  // per made vertex, its triangles at the start
    std::vector<bool> locked_;
    std::vector<std::uint32_t> degree_;  // per vertex, its triangles now
    std::vector<Collapse> collapses_;
    std::vector<std::uint32_t> ownerOf_;  // per triangle, the collapse that changed it, or none
};

}  // namespace

RingCoarseningPass::RingCoarseningPass(MarkedTriangles surface, std::size_t firstMade,
                                       const Judge& judge)
    : surface_(surface), first_(firstMade), judge_(judge) {
    const auto& triangles = surface_.soup.triangles;
    const std::size_t made = surface_.soup.points.size() - first_;
    fanStart_.assign(made + 1, 0);
    for (const auto& t : triangles)
        for (std::uint32_t v : t)
            if (v >= first_) ++fanStart_[v - first_ + 1];
    for (std::size_t i = 0; i < made; ++i) fanStart_[i + 1] += fanStart_[i];
    fan_.resize(fanStart_[made]);
    std::vector<std::uint32_t> next(fanStart_.begin(), fanStart_.end() - 1);
    for (std::size_t t = 0; t < triangles.size(); ++t)
        for (std::uint32_t v : triangles[t])
            if (v >= first_) fan_[next[v - first_]++] = std::uint32_t(t);
    locked_.assign(made, false);
    degree_.assign(surface_.soup.points.size(), 0);
    for (const auto& t : triangles)
        for (std::uint32_t v : t) ++degree_[v];
}

std::vector<std::size_t> RingCoarseningPass::collapse() {
    TriangleSoup& soup = surface_.soup;
    std::vector<bool> gone(soup.triangles.size(), false);
    for (std::uint32_t v = std::uint32_t(first_); v < soup.points.size(); ++v) {
        if (!free(v)) continue;
        const std::vector<std::uint32_t> around = neighbours(v);
        for (std::uint32_t w : around)
            if (w >= first_ && std::abs(soup.points[w].z - soup.points[v].z) <= kSameRingMm &&
                free(w) && tryCollapse(v, w, around, gone))
                break;
    }
    // The two triangles at each collapsed edge go; the rest are renumbered.
    std::vector<std::size_t> newId(soup.triangles.size());
    std::size_t kept = 0;
    for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
        newId[t] = kept;
        if (gone[t]) continue;
        soup.triangles[kept] = soup.triangles[t];
        surface_.pieceOf[kept] = surface_.pieceOf[t];
        surface_.isLoft[kept] = surface_.isLoft[t];
        ++kept;
    }
    soup.triangles.resize(kept);
    surface_.pieceOf.resize(kept);
    surface_.isLoft.resize(kept);
    std::vector<std::uint32_t>().swap(fan_);  // stale from here on
    ownerOf_.assign(kept, kNoCollapse);
    std::vector<std::size_t> changed;
    for (std::size_t c = 0; c < collapses_.size(); ++c)
        for (std::size_t& t : collapses_[c].changed) {
            t = newId[t];
            ownerOf_[t] = std::uint32_t(c);
            changed.push_back(t);
        }
    return changed;
}

bool RingCoarseningPass::free(std::uint32_t v) const {
    if (v < first_ || locked_[v - first_]) return false;
    const std::uint32_t* begin = fan_.data() + fanStart_[v - first_];
    const std::uint32_t* end = fan_.data() + fanStart_[v - first_ + 1];
    if (begin == end) return false;
    const std::uint32_t piece = surface_.pieceOf[*begin];
    for (const std::uint32_t* t = begin; t != end; ++t)
        if (!surface_.isLoft[*t] || surface_.pieceOf[*t] != piece) return false;
    return true;
}

std::vector<std::uint32_t> RingCoarseningPass::neighbours(std::uint32_t v) const {
    std::vector<std::uint32_t> out;
    for (std::uint32_t i = fanStart_[v - first_]; i < fanStart_[v - first_ + 1]; ++i)
        for (std::uint32_t u : surface_.soup.triangles[fan_[i]])
            if (u != v) out.push_back(u);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

bool RingCoarseningPass::follows(const Vec3& p, std::uint32_t v) const {
    const double f = judge_.field.value(p) - judge_.bulgeMm(v, p.z);
    if (std::abs(f) > judge_.options.toleranceMm) return false;
    return !judge_.options.withinNeighbourPlanes || judge_.field.neighbourPlanesValue(p) <= 0;
}

bool RingCoarseningPass::tryCollapse(std::uint32_t v, std::uint32_t w,
                                     const std::vector<std::uint32_t>& nv,
                                     std::vector<bool>& gone) {
    auto& triangles = surface_.soup.triangles;
    const auto& points = surface_.soup.points;
    const std::uint32_t* begin = fan_.data() + fanStart_[v - first_];
    const std::uint32_t* end = fan_.data() + fanStart_[v - first_ + 1];
    if (surface_.pieceOf[*begin] != surface_.pieceOf[fan_[fanStart_[w - first_]]]) return false;
    // Link condition: v and w share exactly the two corners opposite their
    // edge, or the collapse pinches the surface; and none of the four ends
    // with fewer than three triangles (two triangles on the same corners).
    std::vector<std::uint32_t> atEdge, opposite;
    for (const std::uint32_t* t = begin; t != end; ++t) {
        const auto& tri = triangles[*t];
        if (tri[0] != w && tri[1] != w && tri[2] != w) continue;
        atEdge.push_back(*t);
        for (std::uint32_t c : tri)
            if (c != v && c != w) opposite.push_back(c);
    }
    if (atEdge.size() != 2 || opposite.size() != 2 || opposite[0] == opposite[1]) return false;
    if (degree_[v] <= 3 || degree_[w] <= 3 || degree_[opposite[0]] <= 3 ||
        degree_[opposite[1]] <= 3)
        return false;
    const std::vector<std::uint32_t> nw = neighbours(w);
    std::vector<std::uint32_t> common;
    std::set_intersection(nv.begin(), nv.end(), nw.begin(), nw.end(), std::back_inserter(common));
    std::sort(opposite.begin(), opposite.end());
    if (common != opposite) return false;
    const Vec3 pw = points[w];
    for (const std::uint32_t* t = begin; t != end; ++t) {
        if (*t == atEdge[0] || *t == atEdge[1]) continue;
        auto tri = triangles[*t];
        const Vec3 before = normalOf(points[tri[0]], points[tri[1]], points[tri[2]]);
        for (std::uint32_t& c : tri)
            if (c == v) c = w;
        const Vec3 a = points[tri[0]], b = points[tri[1]], c = points[tri[2]];
        const Vec3 after = normalOf(a, b, c);
        const double lengthAfter = length(after);
        if (lengthAfter <= 1e-12 ||
            dot(before, after) < kMinNormalCosine * length(before) * lengthAfter)
            return false;
        if (!follows((1.0 / 3.0) * (a + b + c), w)) return false;
        for (std::uint32_t corner : tri)
            if (corner != w && !follows(0.5 * (pw + points[corner]), w)) return false;
    }
    Collapse made{v,
                  w,
                  {},
                  {triangles[atEdge[0]], triangles[atEdge[1]]},
                  {surface_.pieceOf[atEdge[0]], surface_.pieceOf[atEdge[1]]}};
    for (const std::uint32_t* t = begin; t != end; ++t) {
        if (*t == atEdge[0] || *t == atEdge[1]) {
            gone[*t] = true;
            continue;
        }
        for (std::uint32_t& c : triangles[*t])
            if (c == v) c = w;
        made.changed.push_back(*t);
    }
    collapses_.push_back(std::move(made));
    degree_[w] = degree_[w] + degree_[v] - 4;
    degree_[v] = 0;
    --degree_[opposite[0]];
    --degree_[opposite[1]];
    // No vertex around v takes part in another collapse of this pass: their
    // triangles changed (w's row no longer lists them all), and a collapse
    // that shares no triangle with this one is undone on its own. w's other
    // neighbours are free: their triangles are as they were.
    for (std::uint32_t u : nv)
        if (u >= first_) locked_[u - first_] = true;
    locked_[v - first_] = true;
    return true;
}

std::vector<std::size_t> RingCoarseningPass::undoWhere(const std::vector<bool>& which) {
    auto& triangles = surface_.soup.triangles;
    std::vector<std::size_t> back;
    for (std::size_t c = 0; c < collapses_.size(); ++c) {
        Collapse& collapse = collapses_[c];
        if (!collapse.live || !which[c]) continue;
        collapse.live = false;
        for (std::size_t t : collapse.changed) {
            // The corner that was v is w's only appearance: the triangles
            // that had both were the two removed.
            for (std::uint32_t& corner : triangles[t])
                if (corner == collapse.into) corner = collapse.from;
            ownerOf_[t] = kNoCollapse;
            back.push_back(t);
        }
        for (int k = 0; k < 2; ++k) {
            back.push_back(triangles.size());
            triangles.push_back(collapse.removed[std::size_t(k)]);
            surface_.pieceOf.push_back(collapse.removedPieces[std::size_t(k)]);
            surface_.isLoft.push_back(true);
            ownerOf_.push_back(kNoCollapse);
        }
    }
    return back;
}

std::vector<std::size_t> RingCoarseningPass::undo(const std::vector<std::size_t>& defective) {
    std::vector<bool> which(collapses_.size(), false);
    for (std::size_t t : defective)
        if (t < ownerOf_.size() && ownerOf_[t] != kNoCollapse) which[ownerOf_[t]] = true;
    return undoWhere(which);
}

std::vector<std::size_t> RingCoarseningPass::undoAll() {
    return undoWhere(std::vector<bool>(collapses_.size(), true));
}

std::vector<std::size_t> RingCoarseningPass::liveTriangles() const {
    std::vector<std::size_t> out;
    for (const Collapse& c : collapses_)
        if (c.live) out.insert(out.end(), c.changed.begin(), c.changed.end());
    return out;
}

std::size_t RingCoarseningPass::liveCollapses() const {
    return std::size_t(std::count_if(collapses_.begin(), collapses_.end(),
                                     [](const Collapse& c) { return c.live; }));
}

std::size_t coarsenMiddleRings(MarkedTriangles surface, std::size_t firstMade,
                               const SliceInterpolant& field,
                               const std::function<double(std::size_t, double)>& bulgeMm,
                               const RingCoarseningOptions& options, MeshCheckReport& check) {
    if (!check.validSolid()) return 0;
    const RingCoarseningPass::Judge judge{field, options, bulgeMm};
    std::size_t removed = 0;
    for (int pass = 0; pass < options.passes && firstMade < surface.soup.points.size(); ++pass) {
        RingCoarseningPass coarsening(surface, firstMade, judge);
        std::vector<std::size_t> suspects = coarsening.collapse();
        if (suspects.empty()) break;
        // A collapse under the link condition keeps a closed, oriented
        // manifold closed and oriented; what it can break is what moving
        // vertices can: degenerate or crossing triangles. Undone collapses
        // are as they were before the pass (clean), but next to ones still
        // made: both are searched again, until no collapse left takes part
        // in a defect.
        std::vector<std::size_t> defects = defectsAfterMoving(surface.soup, suspects);
        for (int round = 0; round < kUndoRounds && !defects.empty(); ++round) {
            std::vector<std::size_t> back = coarsening.undo(defects);
            if (back.empty() || round + 1 == kUndoRounds) {
                const std::vector<std::size_t> rest = coarsening.undoAll();
                back.insert(back.end(), rest.begin(), rest.end());
            }
            suspects = coarsening.liveTriangles();
            suspects.insert(suspects.end(), back.begin(), back.end());
            defects = defectsAfterMoving(surface.soup, suspects);
        }
        removed += coarsening.liveCollapses();
        if (coarsening.liveCollapses() == 0) break;
    }
    if (removed > 0) updateReport(check, surface.soup, removed);
    return removed;
}

}  // namespace dfrecon
