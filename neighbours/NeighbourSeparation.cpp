#include "neighbours/NeighbourSeparation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>

#include "field/ClosestPrimitives.hpp"
#include "field/SurfaceScene.hpp"
#include "geometry/Box3.hpp"
#include "geometry/MeshCheck.hpp"
#include "geometry/OrderedParallel.hpp"

namespace dfrecon {

namespace {

constexpr std::uint32_t kEdgeMidpoint = UINT32_MAX;
// A probe at a triangle's centroid: its vertex is made when the triangle is
// split there.
constexpr std::uint32_t kTriangleCentroid = UINT32_MAX - 1;

// Probe-and-move rounds: the first meets in the middle, the second moves
// out what is still inside (a neighbour's move fell short) and splits every
// triangle still passing through a neighbour. Each further round takes
// about a third of what is left for twice the time, the surfaces growing
// with the splits (Brodmann: 413 mm3 left in 11.9 s with two, 279 in 22 s
// with three, 211 in 48 s with four; `dfrecon-bench neighbours`).
constexpr int kRounds = 2;

Box3 boxOf(const TriangleSoup& soup, double marginMm) {
    Box3 box;
    for (const Vec3& p : soup.points) box.add(p);
    const Vec3 margin{marginMm, marginMm, marginMm};
    box.lo = box.lo - margin;
    box.hi = box.hi + margin;
    return box;
}

bool boxContains(const Box3& box, Vec3 p) {
    return p.x >= box.lo.x && p.x <= box.hi.x && p.y >= box.lo.y && p.y <= box.hi.y &&
           p.z >= box.lo.z && p.z <= box.hi.z;
}

// Is plane coordinate z within toleranceMm of one of `planes` (increasing)?
bool onPlane(const std::vector<double>& planes, double z, double toleranceMm) {
    const auto above = std::lower_bound(planes.begin(), planes.end(), z - toleranceMm);
    return above != planes.end() && *above <= z + toleranceMm;
}

double largestGapMm(const std::vector<double>& planes) {
    double gap = 0;
    for (std::size_t k = 1; k < planes.size(); ++k) gap = std::max(gap, planes[k] - planes[k - 1]);
    return gap;
}

// Distances only mean something between surfaces on parallel planes: the
// planes of one set are then the planes of the other.
bool parallelPlanes(const PlaneFrame& a, const PlaneFrame& b) {
    return std::abs(std::abs(dot(a.n, b.n)) - 1) <= 1e-9;
}

// The points of `from` a probe against the surface of `to` asks about: its
// vertices in to's box, the midpoints of its contour edges there and the
// centroids of its triangles between the planes. A point on a plane both
// ROIs have tells whether their contours overlap; a vertex on none of
// from's planes may move. A triangle whose corners all lie outside the
// neighbour can still pass through it (its corners on the planes, which
// never move, the neighbour's vertices beside it): a centroid inside the
// neighbour is where the triangle is split, and its new vertex moves.
struct ProbePoints {
    std::vector<Vec3> points;
    std::vector<std::uint32_t> vertex;    // the vertex, kEdgeMidpoint or kTriangleCentroid
    std::vector<std::uint32_t> triangle;  // for a centroid, its triangle
    std::vector<bool> onSharedPlane;

    void add(Vec3 p, std::uint32_t v, std::uint32_t t, bool shared) {
        points.push_back(p);
        vertex.push_back(v);
        triangle.push_back(t);
        onSharedPlane.push_back(shared);
    }
};

ProbePoints probePoints(const NeighbourSurface& from, const NeighbourSurface& to, const Box3& toBox,
                        double planeToleranceMm, bool withCentroids) {
    const TriangleSoup& soup = *from.surface;
    auto onOwnPlane = [&](Vec3 p) {
        return onPlane(from.planeZMm, dot(p, from.frame.n), planeToleranceMm);
    };
    auto onOtherPlane = [&](Vec3 p) {
        return onPlane(to.planeZMm, dot(p, to.frame.n), planeToleranceMm);
    };
    ProbePoints probe;
    std::vector<bool> own(soup.points.size(), false);
    for (std::uint32_t v = 0; v < soup.points.size(); ++v) {
        const Vec3 p = soup.points[v];
        if (!boxContains(toBox, p)) continue;
        own[v] = onOwnPlane(p);
        // A point on from's plane where `to` has no contour says nothing.
        if (own[v] && !onOtherPlane(p)) continue;
        probe.add(p, v, 0, own[v]);
    }
    // Contour edges are mesh edges with both ends on one plane; each is in
    // two triangles, once each way: taken where it runs from the lower index.
    for (const auto& t : soup.triangles)
        for (std::size_t k = 0; k < 3; ++k) {
            const std::uint32_t u = t[k], w = t[(k + 1) % 3];
            if (u > w || !own[u] || !own[w]) continue;
            const Vec3 mid = 0.5 * (soup.points[u] + soup.points[w]);
            if (std::abs(dot(soup.points[u] - soup.points[w], from.frame.n)) > planeToleranceMm ||
                !onOtherPlane(mid))
                continue;
            probe.add(mid, kEdgeMidpoint, 0, true);
        }
    for (std::uint32_t t = 0; withCentroids && t < soup.triangles.size(); ++t) {
        const auto& tri = soup.triangles[t];
        const Vec3 centroid =
            (1.0 / 3) * (soup.points[tri[0]] + soup.points[tri[1]] + soup.points[tri[2]]);
        if (boxContains(toBox, centroid) && !onOwnPlane(centroid))
            probe.add(centroid, kTriangleCentroid, t, false);
    }
    return probe;
}

// Area-weighted outward normals at the vertices: which way is into the
// solid, for a move that must go inward. O(T).
std::vector<Vec3> vertexNormals(const TriangleSoup& soup) {
    std::vector<Vec3> normals(soup.points.size());
    for (const auto& t : soup.triangles) {
        const Vec3 n =
            cross(soup.points[t[1]] - soup.points[t[0]], soup.points[t[2]] - soup.points[t[0]]);
        for (const std::uint32_t v : t) normals[v] = normals[v] + n;
    }
    return normals;
}

// Where a vertex inside a neighbour goes.
struct Move {
    std::uint32_t vertex = 0;
    Vec3 to;
    double lengthMm = 0;
    std::size_t pair = 0;
    // The neighbour's closest point and triangle the move heads for.
    Vec3 closest;
    std::uint32_t otherTriangle = 0;
};

// A vertex between the planes found inside a neighbour (or a centroid, its
// vertex kTriangleCentroid until its triangle is split), and the
// neighbour's closest point and triangle.
struct Inside {
    std::uint32_t vertex = 0;
    Vec3 closest;
    std::uint32_t triangle = 0;
    std::uint32_t splitTriangle = 0;  // own triangle of a centroid
    Vec3 at;                          // where the centroid lies
};

// What probing one ROI's points against another found.
struct Probe {
    bool overlapOnPlanes = false;
    double deepestMm = 0;
    std::vector<Inside> inside;
};

Probe readProbe(const ProbePoints& probe, const std::vector<ClosestPrimitive>& found,
                double insideToleranceMm) {
    Probe result;
    for (std::size_t k = 0; k < found.size(); ++k) {
        // Beyond the search band (object -1) counts as not inside.
        const double depth = found[k].object < 0 ? 0 : -found[k].distanceMm;
        if (!(depth > insideToleranceMm)) continue;
        if (probe.onSharedPlane[k]) {
            result.overlapOnPlanes = true;
            continue;
        }
        result.deepestMm = std::max(result.deepestMm, depth);
        result.inside.push_back({probe.vertex[k], found[k].point, found[k].triangle,
                                 probe.triangle[k], probe.points[k]});
    }
    return result;
}

// The moves of `mine` (one ROI's vertices inside the other of pair `pair`):
// in the first round halfway to the other's closest point where the
// other's triangle there has a vertex inside this ROI too (both sides move:
// they meet in the middle), else all the way; later rounds (what is still
// inside) all the way; a clearance beyond either way. A closest point
// outward of this surface (a structure inside another without touching its
// planes' contours) is no lens: no move.
// `own` is the ROI whose vertices move, with its vertexNormals.
struct MovingSurface {
    const TriangleSoup& soup;
    const std::vector<Vec3>& normals;
};

// How far a round moves: meeting in the middle (the first) or not, and the
// clearance beyond.
struct RoundRule {
    bool firstRound = true;
    double clearanceMm = 0.01;
};

std::vector<Move> movesOf(const Probe& mine, const Probe& theirs, MovingSurface own,
                          const TriangleSoup& other, std::size_t pair, RoundRule rule) {
    const bool firstRound = rule.firstRound;
    const double clearanceMm = rule.clearanceMm;
    const std::vector<Vec3>& normals = own.normals;
    std::vector<bool> theirsInside(other.points.size(), false);
    for (const Inside& in : theirs.inside)
        if (in.vertex != kTriangleCentroid) theirsInside[in.vertex] = true;
    std::vector<Move> moves;
    for (const Inside& in : mine.inside) {
        if (in.vertex == kTriangleCentroid) continue;  // not split: nothing to move
        const Vec3 from = own.soup.points[in.vertex], toward = in.closest - from;
        if (dot(toward, normals[in.vertex]) >= 0) continue;
        const auto& t = other.triangles[in.triangle];
        const bool bothMove =
            firstRound && (theirsInside[t[0]] || theirsInside[t[1]] || theirsInside[t[2]]);
        const double span = length(toward);
        const double share = std::min(1.0, ((bothMove ? 0.5 : 1.0) * span + clearanceMm) / span);
        moves.push_back(
            {in.vertex, from + share * toward, share * span, pair, in.closest, in.triangle});
    }
    return moves;
}

// Where a vertex stays inside its neighbour (its move `stuck` would have
// made its own surface `own` cross itself), the neighbour gives way: the
// corners of its closest triangle that are off its planes move inward past
// the vertex, by the vertex's depth and the clearance.
std::vector<Move> givingWay(const Move& stuck, const TriangleSoup& own,
                            const NeighbourSurface& other, double planeToleranceMm,
                            double clearanceMm) {
    const Vec3 away = own.points[stuck.vertex] - stuck.closest;
    const double depth = length(away);
    if (!(depth > 0)) return {};
    const Vec3 shift = ((depth + clearanceMm) / depth) * away;
    std::vector<Move> moves;
    for (const std::uint32_t w : other.surface->triangles[stuck.otherTriangle]) {
        const Vec3 p = other.surface->points[w];
        if (onPlane(other.planeZMm, dot(p, other.frame.n), planeToleranceMm)) continue;
        moves.push_back({w, p + shift, depth + clearanceMm, stuck.pair, {}, 0});
    }
    return moves;
}

// The signed distances of `points` to the scene's one surface, within bandMm.
std::vector<ClosestPrimitive> distancesTo(ocl::Runtime* runtime, const SurfaceScene& scene,
                                          const std::vector<Vec3>& points, double bandMm) {
    if (points.empty()) return {};
    DistanceQuery query;
    query.maxDistanceMm = bandMm;
    if (!runtime) return closestPrimitivesAtReference(scene, points, query);
    ClosestPrimitiveKernel kernel(*runtime, scene);
    return kernel.runAt(points, query);
}

// Moves `moves` (one per vertex) into `soup`; a move around a collision or
// degenerate triangle is halved, up to kHalvings times, then undone, until
// none is left (the soup was a valid solid, and its triangles do not
// change). Returns which moves stayed, in full or in part.
constexpr int kHalvings = 3;

Vec3 asFloat(Vec3 p) {
    return {double(float(p.x)), double(float(p.y)), double(float(p.z))};
}

std::vector<bool> applyMoves(TriangleSoup& soup, const std::vector<Move>& moves) {
    std::vector<std::int64_t> moveOf(soup.points.size(), -1);
    std::vector<Vec3> before(moves.size());
    std::vector<int> halvings(moves.size(), 0);
    std::vector<bool> changed(soup.points.size(), false);
    for (std::size_t m = 0; m < moves.size(); ++m) {
        const std::uint32_t v = moves[m].vertex;
        moveOf[v] = std::int64_t(m);
        changed[v] = true;
        before[m] = soup.points[v];
        // As mesh files hold them: the check then judges what is written.
        soup.points[v] = asFloat(moves[m].to);
    }
    std::vector<bool> kept(moves.size(), true);
    for (;;) {
        // Only triangles whose corners changed since the last search can
        // collide anew: the moved ones first, then those around changed moves.
        std::vector<std::size_t> suspects;
        for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
            const auto& tri = soup.triangles[t];
            if (changed[tri[0]] || changed[tri[1]] || changed[tri[2]]) suspects.push_back(t);
        }
        std::fill(changed.begin(), changed.end(), false);
        bool again = false;
        for (const std::size_t t : defectsAfterMoving(soup, suspects))
            for (const std::uint32_t v : soup.triangles[t]) {
                if (moveOf[v] < 0 || changed[v]) continue;
                const std::size_t m = std::size_t(moveOf[v]);
                changed[v] = again = true;
                if (++halvings[m] <= kHalvings) {
                    soup.points[v] = asFloat(before[m] + 0.5 * (soup.points[v] - before[m]));
                } else {
                    soup.points[v] = before[m];
                    kept[m] = false;
                    moveOf[v] = -1;
                }
            }
        if (!again) return kept;
    }
}

// Applies the moves of every ROI (deduplicated: each vertex once, as far as
// its deepest neighbour asks), each surface checked on its own, two at once
// on the free cores. Returns per ROI which of its (deduplicated) moves stayed.
std::vector<std::vector<bool>> applyAll(std::vector<NeighbourSurface>& rois,
                                        std::vector<std::vector<Move>>& movesOfRoi) {
    for (std::vector<Move>& moves : movesOfRoi) {
        std::stable_sort(moves.begin(), moves.end(), [](const Move& x, const Move& y) {
            return x.vertex != y.vertex ? x.vertex < y.vertex : x.lengthMm > y.lengthMm;
        });
        moves.erase(std::unique(moves.begin(), moves.end(),
                                [](const Move& x, const Move& y) { return x.vertex == y.vertex; }),
                    moves.end());
    }
    std::vector<std::vector<bool>> kept(rois.size());
    forEachInOrder(
        rois.size(), defaultJobs(rois.size()),
        [&](std::size_t i, std::size_t) {
            return movesOfRoi[i].empty() ? std::vector<bool>{}
                                         : applyMoves(*rois[i].surface, movesOfRoi[i]);
        },
        [&](std::size_t i, std::vector<bool> done) { kept[i] = std::move(done); });
    return kept;
}

// Cells of about bandMm that lie within bandMm of a surface's triangles: a
// point in no such cell is farther than the band from it, and needs no
// search. O(T) to build (the cells each triangle's box, grown by the band,
// covers), O(1) to ask. (geometry/BoxGrid over the grown boxes answers the
// same, exactly, but visits every box of a cell per point: on the Brodmann
// set the separation took 13.6 s with it against 8.6 s with this.)
class NearSurface {
  public:
    NearSurface(const TriangleSoup& soup, const Box3& box, double bandMm)
        : origin_(box.lo - Vec3{bandMm, bandMm, bandMm}), cellMm_(std::max(bandMm, 1e-3)) {
        const Vec3 size = box.hi - box.lo;
        // At most about 16 M cells: a coarser grid only asks more searches.
        const double cells =
            (size.x / cellMm_ + 3) * (size.y / cellMm_ + 3) * (size.z / cellMm_ + 3);
        if (cells > 16e6) cellMm_ *= std::cbrt(cells / 16e6);
        for (int k = 0; k < 3; ++k) count_[k] = std::size_t(axis(size, k) / cellMm_) + 3;
        near_.assign(count_[0] * count_[1] * count_[2], false);
        for (const auto& t : soup.triangles) {
            Box3 b;
            for (const std::uint32_t v : t) b.add(soup.points[v]);
            const Vec3 lo = b.lo - Vec3{bandMm, bandMm, bandMm},
                       hi = b.hi + Vec3{bandMm, bandMm, bandMm};
            const std::size_t i0 = cell(lo, 0), i1 = cell(hi, 0), j0 = cell(lo, 1),
                              j1 = cell(hi, 1), k0 = cell(lo, 2), k1 = cell(hi, 2);
            for (std::size_t k = k0; k <= k1; ++k)
                for (std::size_t j = j0; j <= j1; ++j)
                    for (std::size_t i = i0; i <= i1; ++i)
                        near_[(k * count_[1] + j) * count_[0] + i] = true;
        }
    }
    bool maybeNear(Vec3 p) const {
        return near_[(cell(p, 2) * count_[1] + cell(p, 1)) * count_[0] + cell(p, 0)];
    }

  private:
    static double axis(Vec3 v, int k) { return k == 0 ? v.x : (k == 1 ? v.y : v.z); }
    std::size_t cell(Vec3 p, int k) const {
        const double c = std::floor((axis(p, k) - axis(origin_, k)) / cellMm_);
        return std::size_t(std::clamp(c, 0.0, double(count_[std::size_t(k)] - 1)));
    }
    Vec3 origin_;
    double cellMm_;
    std::size_t count_[3] = {1, 1, 1};
    std::vector<bool> near_;
};

// Splits every triangle of `soup` whose centroid `probes` found inside a
// neighbour at that centroid (once, whichever pairs found it; unless
// `evenWithCornerInside`, only those with no corner found inside) and gives
// those probes the new vertex, which then moves like any other. The
// surface keeps its shape and orientation: three triangles in the old
// one's plane, the old index holding the first. Splits whose new triangles
// cross another or fold are taken back. O(T + splits), plus a local check
// around the new triangles.
void splitAtCentroids(TriangleSoup& soup, const std::vector<Probe*>& probes,
                      bool evenWithCornerInside) {
    const std::size_t pointsBefore = soup.points.size(), trianglesBefore = soup.triangles.size();
    std::vector<bool> vertexInside(pointsBefore, false);
    for (const Probe* probe : probes)
        for (const Inside& in : probe->inside)
            if (in.vertex != kTriangleCentroid) vertexInside[in.vertex] = true;
    // Every split made at once, appended: split k's vertex is
    // pointsBefore + k, its triangles splitOf[k] and trianglesBefore + 2k,
    // + 2k + 1.
    std::vector<std::uint32_t> splitOf;
    std::vector<std::array<std::uint32_t, 3>> original;
    constexpr std::uint32_t kNotSplit = UINT32_MAX;
    std::vector<std::uint32_t> splitIndex(trianglesBefore, kNotSplit);  // per triangle: its k
    for (const Probe* probe : probes)
        for (const Inside& in : probe->inside) {
            if (in.vertex != kTriangleCentroid || splitIndex[in.splitTriangle] != kNotSplit)
                continue;
            // In the first round a corner inside moves out itself, most
            // often taking the triangle along; splitting those too there
            // cost three times the collision checks (Brodmann: 28 s
            // against 11 s) for a fifth less overlap. In the next, few
            // corners are left inside and every triangle through a
            // neighbour is split (593 -> 413 mm3, 10.8 -> 11.9 s).
            const auto old = soup.triangles[in.splitTriangle];
            if (!evenWithCornerInside &&
                (vertexInside[old[0]] || vertexInside[old[1]] || vertexInside[old[2]]))
                continue;
            const auto made = std::uint32_t(soup.points.size());
            splitIndex[in.splitTriangle] = std::uint32_t(splitOf.size());
            splitOf.push_back(in.splitTriangle);
            original.push_back(old);
            // As mesh files hold it, like every point the checks see.
            soup.points.push_back(asFloat(in.at));
            soup.triangles[in.splitTriangle] = {old[0], old[1], made};
            soup.triangles.push_back({old[1], old[2], made});
            soup.triangles.push_back({old[2], old[0], made});
        }
    if (splitOf.empty()) return;
    // The new point, rounded to float, lies a hair off its triangle's
    // plane: where that makes the new triangles cross another or fold, the
    // split is taken back.
    std::vector<std::size_t> fresh(splitOf.begin(), splitOf.end());
    for (std::size_t t = trianglesBefore; t < soup.triangles.size(); ++t) fresh.push_back(t);
    std::vector<bool> undo(splitOf.size(), false);
    for (const std::size_t t : defectsAfterMoving(soup, fresh)) {
        if (t >= trianglesBefore)
            undo[(t - trianglesBefore) / 2] = true;
        else if (splitIndex[t] != kNotSplit)
            undo[splitIndex[t]] = true;
    }
    // Keep the splits that stay, in order, compacting the appended tails.
    std::vector<std::uint32_t> vertexOf(splitOf.size(), kTriangleCentroid);
    std::size_t kept = 0;
    for (std::size_t k = 0; k < splitOf.size(); ++k) {
        if (undo[k]) {
            soup.triangles[splitOf[k]] = original[k];
            continue;
        }
        const auto made = std::uint32_t(pointsBefore + kept);
        soup.points[made] = soup.points[pointsBefore + k];
        const auto& old = original[k];
        soup.triangles[splitOf[k]] = {old[0], old[1], made};
        soup.triangles[trianglesBefore + 2 * kept] = {old[1], old[2], made};
        soup.triangles[trianglesBefore + 2 * kept + 1] = {old[2], old[0], made};
        vertexOf[k] = made;
        ++kept;
    }
    soup.points.resize(pointsBefore + kept);
    soup.triangles.resize(trianglesBefore + 2 * kept);
    for (Probe* probe : probes)
        for (Inside& in : probe->inside)
            if (in.vertex == kTriangleCentroid && splitIndex[in.splitTriangle] != kNotSplit)
                in.vertex = vertexOf[splitIndex[in.splitTriangle]];
}

// How many of a probe's points inside are vertices (a centroid is one once
// its triangle was split).
std::size_t verticesInside(const Probe& probe) {
    return std::size_t(
        std::count_if(probe.inside.begin(), probe.inside.end(),
                      [](const Inside& in) { return in.vertex != kTriangleCentroid; }));
}

// Every ROI of a pair probed against the other: one hierarchy per ROI,
// asked about the points of its neighbours within its box and band.
struct Probes {
    std::vector<Probe> ofA, ofB;  // per pair: a's points in b, b's in a
};

Probes probePairs(ocl::Runtime* runtime, const std::vector<NeighbourSurface>& rois,
                  const std::vector<NeighbourPair>& pairs, const std::vector<bool>& active,
                  const NeighbourSeparationOptions& options) {
    const std::size_t count = rois.size();
    std::vector<std::vector<std::size_t>> pairsOf(count);
    for (std::size_t p = 0; p < pairs.size(); ++p) {
        if (!active[p]) continue;
        pairsOf[pairs[p].a].push_back(p);
        pairsOf[pairs[p].b].push_back(p);
    }
    Probes result;
    result.ofA.resize(pairs.size());
    result.ofB.resize(pairs.size());
    for (std::size_t to = 0; to < count; ++to) {
        if (pairsOf[to].empty()) continue;
        const Box3 box = boxOf(*rois[to].surface, options.insideToleranceMm);
        double bandMm = largestGapMm(rois[to].planeZMm);
        for (const std::size_t p : pairsOf[to])
            bandMm = std::max(
                bandMm, largestGapMm(rois[pairs[p].a == to ? pairs[p].b : pairs[p].a].planeZMm));
        // A single plane each has no gap: a band of a centimetre then.
        if (!(bandMm > 0)) bandMm = 10;
        const NearSurface near(*rois[to].surface, box, bandMm);
        std::vector<ProbePoints> probes;
        std::vector<Vec3> points;
        for (const std::size_t p : pairsOf[to]) {
            const std::size_t from = pairs[p].a == to ? pairs[p].b : pairs[p].a;
            // Only a separation splits triangles: a report counts vertices.
            ProbePoints probe =
                probePoints(rois[from], rois[to], box, options.planeToleranceMm, options.move);
            ProbePoints kept;
            for (std::size_t k = 0; k < probe.points.size(); ++k)
                if (near.maybeNear(probe.points[k])) {
                    kept.add(probe.points[k], probe.vertex[k], probe.triangle[k],
                             probe.onSharedPlane[k]);
                }
            points.insert(points.end(), kept.points.begin(), kept.points.end());
            probes.push_back(std::move(kept));
        }
        if (points.empty()) continue;
        const SurfaceScene scene({*rois[to].surface}, {rois[to].name},
                                 SurfaceScene::KnownValidSolids{});
        const std::vector<ClosestPrimitive> found = distancesTo(runtime, scene, points, bandMm);
        std::size_t first = 0;
        for (std::size_t k = 0; k < probes.size(); ++k) {
            const std::size_t p = pairsOf[to][k], size = probes[k].points.size();
            const std::vector<ClosestPrimitive> mine(found.begin() + std::ptrdiff_t(first),
                                                     found.begin() + std::ptrdiff_t(first + size));
            first += size;
            (pairs[p].a == to ? result.ofB : result.ofA)[p] =
                readProbe(probes[k], mine, options.insideToleranceMm);
        }
    }
    return result;
}

}  // namespace

NeighbourSeparation keepNeighboursApart(ocl::Runtime* runtime, std::vector<NeighbourSurface>& rois,
                                        const NeighbourSeparationOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    const std::size_t count = rois.size();
    std::vector<Box3> boxes(count);
    for (std::size_t i = 0; i < count; ++i)
        boxes[i] = boxOf(*rois[i].surface, options.insideToleranceMm);

    // Candidate pairs: boxes that overlap, planes that are parallel.
    std::vector<NeighbourPair> pairs;
    for (std::size_t a = 0; a < count; ++a)
        for (std::size_t b = a + 1; b < count; ++b)
            if (boxes[a].overlaps(boxes[b]) && parallelPlanes(rois[a].frame, rois[b].frame))
                pairs.push_back({a, b});
    NeighbourSeparation result;
    result.measures.resize(count);
    std::vector<bool> active(pairs.size(), true), moved(count, false);
    const int rounds = options.move ? kRounds : 1;
    for (int round = 0; round < rounds; ++round) {
        Probes probes = probePairs(runtime, rois, pairs, active, options);
        // Triangles found passing through a neighbour get their vertex to
        // move (pairs overlapping on planes are left as drawn).
        for (std::size_t i = 0; options.move && i < count; ++i) {
            std::vector<Probe*> mine;
            for (std::size_t p = 0; p < pairs.size(); ++p) {
                const bool onPlanes =
                    round == 0 ? probes.ofA[p].overlapOnPlanes || probes.ofB[p].overlapOnPlanes
                               : pairs[p].overlapOnPlanes;
                if (!active[p] || onPlanes) continue;
                if (pairs[p].a == i) mine.push_back(&probes.ofA[p]);
                if (pairs[p].b == i) mine.push_back(&probes.ofB[p]);
            }
            splitAtCentroids(*rois[i].surface, mine, round > 0);
        }
        std::vector<std::vector<Move>> movesOfRoi(count);
        // Each ROI's normals once a round, for all its pairs.
        std::vector<std::vector<Vec3>> normalsOf(count);
        auto normals = [&](std::size_t i) -> const std::vector<Vec3>& {
            if (normalsOf[i].empty()) normalsOf[i] = vertexNormals(*rois[i].surface);
            return normalsOf[i];
        };
        for (std::size_t p = 0; p < pairs.size(); ++p) {
            if (!active[p]) continue;
            NeighbourPair& pair = pairs[p];
            const Probe &ofA = probes.ofA[p], &ofB = probes.ofB[p];
            if (round == 0) {
                pair.overlapOnPlanes = ofA.overlapOnPlanes || ofB.overlapOnPlanes;
                pair.insideA = verticesInside(ofA);
                pair.insideB = verticesInside(ofB);
                pair.deepestMm = std::max(ofA.deepestMm, ofB.deepestMm);
            }
            pair.leftInsideA = verticesInside(ofA);
            pair.leftInsideB = verticesInside(ofB);
            active[p] = options.move && !pair.overlapOnPlanes &&
                        !ofA.inside.empty() + !ofB.inside.empty() > 0;
            if (!active[p]) continue;
            const TriangleSoup &a = *rois[pair.a].surface, &b = *rois[pair.b].surface;
            const RoundRule rule{round == 0, options.clearanceMm};
            for (const Move& m : movesOf(ofA, ofB, {a, normals(pair.a)}, b, p, rule))
                movesOfRoi[pair.a].push_back(m);
            for (const Move& m : movesOf(ofB, ofA, {b, normals(pair.b)}, a, p, rule))
                movesOfRoi[pair.b].push_back(m);
        }
        const std::vector<std::vector<bool>> kept = applyAll(rois, movesOfRoi);
        std::vector<std::vector<Move>> giving(count);
        for (std::size_t i = 0; i < count; ++i) {
            if (!movesOfRoi[i].empty()) moved[i] = true;
            for (std::size_t m = 0; m < kept[i].size(); ++m) {
                const Move& move = movesOfRoi[i][m];
                NeighbourPair& pair = pairs[move.pair];
                if (!kept[i][m]) {
                    // After the last round, neighbours give way to the stuck.
                    if (round + 1 < rounds) continue;
                    const std::size_t other = pair.a == i ? pair.b : pair.a;
                    for (const Move& g : givingWay(move, *rois[i].surface, rois[other],
                                                   options.planeToleranceMm, options.clearanceMm))
                        giving[other].push_back(g);
                    continue;
                }
                if (round == 0) ++(pair.a == i ? pair.movedA : pair.movedB);
                // The last round's moves are not probed again: a kept move
                // leaves its vertex outside.
                if (round + 1 == rounds) {
                    std::size_t& left = pair.a == i ? pair.leftInsideA : pair.leftInsideB;
                    left -= left > 0 ? 1 : 0;
                }
            }
        }
        if (round + 1 == rounds) {
            applyAll(rois, giving);
            for (std::size_t i = 0; i < count; ++i)
                if (!giving[i].empty()) moved[i] = true;
        }
    }
    for (std::size_t i = 0; i < count; ++i)
        if (moved[i]) result.measures[i] = measureSurface(*rois[i].surface);
    for (const NeighbourPair& pair : pairs)
        if (pair.insideA + pair.insideB > 0 || pair.overlapOnPlanes) result.pairs.push_back(pair);
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace dfrecon
