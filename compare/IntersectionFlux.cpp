#include "compare/IntersectionFlux.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include "field/Rasterization.hpp"
#include "geometry/Box3.hpp"
#include "geometry/CoreBudget.hpp"

namespace dfrecon {

namespace {

using PredicateKernel = CGAL::Exact_predicates_inexact_constructions_kernel;

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
// Shares of the pair search (each a slab of A's boxes along x): a fixed
// number, so that results do not depend on the cores free.
constexpr std::size_t kPairShares = 8;

// +1 where x lies on the side that triangle abc's normal (b − a) × (c − a)
// points to (outside, for a surface oriented outward), −1 on the other side,
// 0 on its plane. Exact (CGAL's filtered predicate).
int sideOf(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& x) {
    // CGAL's orientation is the sign of det(b − a, c − a, x − a).
    return int(CGAL::orientation(
        PredicateKernel::Point_3(a.x, a.y, a.z), PredicateKernel::Point_3(b.x, b.y, b.z),
        PredicateKernel::Point_3(c.x, c.y, c.z), PredicateKernel::Point_3(x.x, x.y, x.z)));
}

double det(const Vec3& a, const Vec3& b, const Vec3& c) {
    return dot(a, cross(b, c));
}

// A constructed crossing point and how far it may lie from the true one:
// along its edge (the rounding of the plane test moves it there, up to the
// whole edge where the edge runs nearly in the plane), of which only the
// part along the crossed plane's normal changes the volume, and by rounding
// in any direction.
struct BoundedPoint {
    Vec3 p;                   // relative to the common origin
    double alongMm = 0;       // along the edge
    double offPlaneMm = 0;    // the same displacement's part normal to the crossed plane
    double roundingMm = 0;    // in any direction
    bool constructed = true;  // false: a corner of a triangle, only rounded to the origin
};

// Where segment pq crosses the plane of triangle abc, p and q lying strictly
// on either side (exactly), in double: t = dp / (dp − dq) from the two
// determinants, whose rounding (≤ 1e-14 of the product of the lengths that
// bound them) bounds t's. Deterministic: the same inputs in the same order
// give the same bits, so both surfaces' regions share the point exactly.
BoundedPoint crossingPoint(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                           const Vec3& c, const Vec3& origin) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a, aq = q - a;
    const double dp = det(ab, ac, ap), dq = det(ab, ac, aq);
    const double scale = length(ab) * length(ac);
    const double errorP = 1e-14 * scale * length(ap), errorQ = 1e-14 * scale * length(aq);
    const double apart = std::abs(dp - dq);
    double t = apart > 0 ? dp / (dp - dq) : 0.5;
    t = std::clamp(t, 0.0, 1.0);
    const double slack = apart - errorP - errorQ;
    const double errorT = slack > 0 ? (errorP + errorQ) / slack + 4 * kEpsilon : 1.0;
    const Vec3 pq = q - p;
    const double normal = length(cross(ab, ac));
    BoundedPoint x;
    x.p = (p + t * pq) - origin;
    x.alongMm = errorT * length(pq);
    // The edge rises |dp − dq| / |n| over its length off the plane.
    x.offPlaneMm = normal > 0 ? errorT * apart / normal : x.alongMm;
    x.roundingMm = 4 * kEpsilon * (length(p) + length(q) + length(origin) + length(x.p));
    return x;
}

// Kahan–Babuška summation: the flux is a sum of many terms of either sign.
struct CompensatedSum {
    double sum = 0, carry = 0;
    void add(double x) {
        const double t = sum + x;
        carry += std::abs(sum) >= std::abs(x) ? (sum - t) + x : (x - t) + sum;
        sum = t;
    }
    double value() const { return sum + carry; }
};

// Where one undirected edge of a surface crosses a triangle of the other.
struct Crossing {
    std::uint32_t edge;
    double t;  // along the edge from its lower point id
    BoundedPoint point;
    bool lowOutside;  // the edge's lower point lies outside the other triangle's plane
};

// What one share of the pair search found: its part of the sums, and the
// crossings of each surface's edges it met.
struct PairShare {
    CompensatedSum volume, bound;
    std::size_t crossingPairs = 0;
    std::vector<Crossing> crossingsA, crossingsB;
};

// One of the two surfaces as the cut sees it: its points (B's moved), its
// undirected edges, where the other surface crosses them, and which of its
// points lie inside the other solid.
struct Side {
    TriangleSoup soup;                                 // B's moved: the points the predicates see
    std::vector<std::array<std::uint32_t, 2>> edges;   // lower id first
    std::vector<std::array<std::uint32_t, 3>> edgeOf;  // per triangle, edge k joins corners k, k+1
    std::vector<std::uint32_t> ownerOf;                // per edge, the first triangle that has it
    std::vector<double> diameter2;                     // per triangle, its longest edge²
    std::vector<double> edgeDiameter2;       // per edge, its triangles' largest diameter²
    std::vector<Crossing> crossings;         // sorted by edge, then t, once complete
    std::vector<std::size_t> firstCrossing;  // per edge, into crossings (edges + 1)
    std::vector<std::int8_t> inside;         // per point: 1 inside the other, 0 not, -1 unknown

    Side(const TriangleSoup& s, const Vec3& shift) : soup(s) {
        for (Vec3& p : soup.points) p = p + shift;
        buildEdges();
    }

    void buildEdges() {
        const std::size_t n = soup.triangles.size();
        struct Use {
            std::uint64_t key;
            std::uint32_t triangle, corner;
        };
        std::vector<Use> uses;
        uses.reserve(3 * n);
        for (std::uint32_t t = 0; t < n; ++t)
            for (std::uint32_t k = 0; k < 3; ++k) {
                const std::uint32_t u = soup.triangles[t][k], v = soup.triangles[t][(k + 1) % 3];
                const std::uint64_t key = (std::uint64_t(std::min(u, v)) << 32) | std::max(u, v);
                uses.push_back({key, t, k});
            }
        std::sort(uses.begin(), uses.end(), [](const Use& x, const Use& y) {
            return x.key != y.key ? x.key < y.key : x.triangle < y.triangle;
        });
        edgeOf.assign(n, {0, 0, 0});
        diameter2.resize(n);
        for (std::size_t t = 0; t < n; ++t) {
            const Vec3 &a = soup.points[soup.triangles[t][0]],
                       &b = soup.points[soup.triangles[t][1]],
                       &c = soup.points[soup.triangles[t][2]];
            diameter2[t] = std::max({dot(b - a, b - a), dot(c - b, c - b), dot(a - c, a - c)});
        }
        for (std::size_t i = 0; i < uses.size(); ++i) {
            if (i == 0 || uses[i].key != uses[i - 1].key) {
                edges.push_back({std::uint32_t(uses[i].key >> 32), std::uint32_t(uses[i].key)});
                ownerOf.push_back(uses[i].triangle);
                edgeDiameter2.push_back(0);
            }
            edgeOf[uses[i].triangle][uses[i].corner] = std::uint32_t(edges.size() - 1);
            edgeDiameter2.back() = std::max(edgeDiameter2.back(), diameter2[uses[i].triangle]);
        }
    }

    void sortCrossings() {
        std::sort(crossings.begin(), crossings.end(), [](const Crossing& x, const Crossing& y) {
            return x.edge != y.edge ? x.edge < y.edge : x.t < y.t;
        });
        firstCrossing.assign(edges.size() + 1, 0);
        for (const Crossing& c : crossings) ++firstCrossing[c.edge + 1];
        for (std::size_t e = 0; e < edges.size(); ++e) firstCrossing[e + 1] += firstCrossing[e];
    }
    std::size_t crossingCount(std::size_t edge) const {
        return firstCrossing[edge + 1] - firstCrossing[edge];
    }
};

// Whether x lies inside the closed surface `solid`: field/Rasterization's
// ray parity, exact on the points as given (a symbolic perturbation where
// the ray meets an edge), for a one-voxel grid centred at x. O(triangles).
bool insideSolid(const TriangleSoup& solid, const Vec3& x) {
    VolumeGeometry one;
    one.size = {1, 1, 1};
    one.originMm = {x.x, x.y, x.z};
    return !voxelsInsideSolid(solid, PlaneFrame{}, one).empty();
}

// Which points of `side` lie inside the other solid: from every edge the
// other surface crosses once (its lower point is inside exactly when it
// lies behind the crossed triangle's plane), then along edges (an odd
// number of crossings flips), with the exact ray parity for shells that no
// crossing reaches. False where two ways disagree (cannot happen in general
// position with exact predicates: a check, not a repair).
bool classifyPoints(Side& side, const Side& other) {
    const std::size_t n = side.soup.points.size();
    side.inside.assign(n, -1);
    // Points' neighbours along edges, with the edge's parity.
    std::vector<std::size_t> first(n + 1, 0);
    for (const auto& e : side.edges) ++first[e[0] + 1], ++first[e[1] + 1];
    for (std::size_t i = 0; i < n; ++i) first[i + 1] += first[i];
    std::vector<std::pair<std::uint32_t, std::uint8_t>> next(first[n]);
    std::vector<std::size_t> fill(first.begin(), first.end() - 1);
    for (std::size_t e = 0; e < side.edges.size(); ++e) {
        const std::uint8_t odd = std::uint8_t(side.crossingCount(e) % 2);
        next[fill[side.edges[e][0]]++] = {side.edges[e][1], odd};
        next[fill[side.edges[e][1]]++] = {side.edges[e][0], odd};
    }
    std::vector<std::uint32_t> queue;
    auto spread = [&](std::uint32_t seed, std::int8_t status) {
        if (side.inside[seed] >= 0) return side.inside[seed] == status;
        side.inside[seed] = status;
        queue.assign(1, seed);
        while (!queue.empty()) {
            const std::uint32_t u = queue.back();
            queue.pop_back();
            for (std::size_t k = first[u]; k < first[u + 1]; ++k) {
                const auto [v, odd] = next[k];
                const std::int8_t expected = std::int8_t(side.inside[u] ^ odd);
                if (side.inside[v] < 0) {
                    side.inside[v] = expected;
                    queue.push_back(v);
                } else if (side.inside[v] != expected) {
                    return false;
                }
            }
        }
        return true;
    };
    for (std::size_t e = 0; e < side.edges.size(); ++e)
        if (side.crossingCount(e) == 1 &&
            !spread(side.edges[e][0], side.crossings[side.firstCrossing[e]].lowOutside ? 0 : 1))
            return false;
    for (std::uint32_t p = 0; p < n; ++p) {
        if (side.inside[p] >= 0) continue;
        if (first[p] == first[p + 1]) continue;  // a point no triangle uses
        // A shell the other surface never crosses: wholly in or out (its
        // points are off that surface, else some pair would have been in no
        // general position).
        if (!spread(p, insideSolid(other.soup, side.soup.points[p]) ? 1 : 0)) return false;
    }
    return true;
}

// The flux of x/3 through the parts of `side`'s triangles that lie inside
// the other solid, as the triangles' edge pieces: each triangle's share is
// a fan from its first corner over its boundary pieces (the segments were
// added as the pairs were cut). Adds to `volume` and the bound to `bound`.
void addEdgePieces(const Side& side, const Vec3& origin, CompensatedSum& volume,
                   CompensatedSum& bound) {
    std::vector<BoundedPoint> along;
    for (std::size_t t = 0; t < side.soup.triangles.size(); ++t) {
        const auto& tri = side.soup.triangles[t];
        const Vec3 apex = side.soup.points[tri[0]] - origin;
        const double apexLength = length(apex);
        // The fan's triangles at a point move the volume by at most
        // diameter²/6 per mm the point moves (the volume's gradient at a
        // vertex is a third of its link's vector area). Constructed points'
        // errors are counted once, where they are made.
        const double fan = side.diameter2[t] / 6;
        auto add = [&](const BoundedPoint& a, const BoundedPoint& b) {
            volume.add(det(apex, a.p, b.p) / 6);
            bound.add(
                fan * ((a.constructed ? 0 : a.roundingMm) + (b.constructed ? 0 : b.roundingMm)) +
                2 * kEpsilon * apexLength * length(a.p) * length(b.p) / 6);
        };
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t u = tri[k], w = tri[(k + 1) % 3];
            const std::uint32_t e = side.edgeOf[t][k];
            const Vec3 pu = side.soup.points[u] - origin, pw = side.soup.points[w] - origin;
            const BoundedPoint from{pu, 0, 0, kEpsilon * (length(pu) + length(origin)), false},
                to{pw, 0, 0, kEpsilon * (length(pw) + length(origin)), false};
            bool in = side.inside[u] == 1;
            const std::size_t count = side.crossingCount(e);
            if (count == 0) {
                if (in) add(from, to);
                continue;
            }
            along.clear();
            for (std::size_t c = side.firstCrossing[e]; c < side.firstCrossing[e + 1]; ++c)
                along.push_back(side.crossings[c].point);
            if (u != side.edges[e][0]) std::reverse(along.begin(), along.end());
            BoundedPoint previous = from;
            for (const BoundedPoint& x : along) {
                if (in) add(previous, x);
                previous = x;
                in = !in;
            }
            if (in) add(previous, to);
        }
    }
}

}  // namespace

IntersectionFlux intersectionByFlux(const TriangleSoup& a, const TriangleSoup& b,
                                    const Vec3& shiftOfB) {
    IntersectionFlux result;
    if (a.triangles.empty() || b.triangles.empty()) {
        result.generalPosition = true;
        return result;
    }
    Side sideA(a, {0, 0, 0}), sideB(b, shiftOfB);
    Box3 all, boundsA, boundsB;
    for (const Vec3& p : sideA.soup.points) boundsA.add(p);
    for (const Vec3& p : sideB.soup.points) boundsB.add(p);
    all.add(boundsA);
    all.add(boundsB);
    // Terms are summed about the middle, where they are smallest.
    const Vec3 origin = 0.5 * (all.lo + all.hi);

    using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::uint32_t>;
    // Only a triangle that reaches into the other surface's box can cross
    // it (neighbours share a sliver of their boxes: most triangles do not).
    auto boxesOf = [](const Side& s, const Box3& other) {
        std::vector<Box> boxes;
        for (std::uint32_t t = 0; t < s.soup.triangles.size(); ++t) {
            const auto& tri = s.soup.triangles[t];
            double lo[3], hi[3];
            for (int axis = 0; axis < 3; ++axis) {
                const double x = s.soup.points[tri[0]][axis], y = s.soup.points[tri[1]][axis],
                             z = s.soup.points[tri[2]][axis];
                lo[axis] = std::min({x, y, z});
                hi[axis] = std::max({x, y, z});
            }
            if (lo[0] > other.hi.x || hi[0] < other.lo.x || lo[1] > other.hi.y ||
                hi[1] < other.lo.y || lo[2] > other.hi.z || hi[2] < other.lo.z)
                continue;
            boxes.emplace_back(lo, hi, t);
        }
        return boxes;
    };
    std::vector<Box> boxesA = boxesOf(sideA, boundsB), boxesB = boxesOf(sideB, boundsA);

    // Thrown out of the pair search at the first pair in no general
    // position: the rest of the search would be wasted (the caller moves B
    // and starts again).
    struct Degenerate {};
    // One pair of triangles whose boxes overlap: do they cross, and if so
    // the segment, its direction, and the crossings of edges it ends on.
    auto cut = [&](PairShare& out, const Box& boxA, const Box& boxB) {
        const std::uint32_t i = boxA.info(), j = boxB.info();
        const auto& ta = a.triangles[i];
        const auto& tb = b.triangles[j];
        const Vec3 pa[3] = {sideA.soup.points[ta[0]], sideA.soup.points[ta[1]],
                            sideA.soup.points[ta[2]]};
        const Vec3 pb[3] = {sideB.soup.points[tb[0]], sideB.soup.points[tb[1]],
                            sideB.soup.points[tb[2]]};
        int sa[3], sb[3];  // A's corners against B's plane, B's against A's
        for (int k = 0; k < 3; ++k) sa[k] = sideOf(pb[0], pb[1], pb[2], pa[k]);
        if ((sa[0] > 0 && sa[1] > 0 && sa[2] > 0) || (sa[0] < 0 && sa[1] < 0 && sa[2] < 0)) return;
        for (int k = 0; k < 3; ++k) sb[k] = sideOf(pa[0], pa[1], pa[2], pb[k]);
        if ((sb[0] > 0 && sb[1] > 0 && sb[2] > 0) || (sb[0] < 0 && sb[1] < 0 && sb[2] < 0)) return;
        if (sa[0] * sa[1] * sa[2] == 0 || sb[0] * sb[1] * sb[2] == 0) {
            throw Degenerate{};
        }
        // Each end of the segment is an edge of one triangle through the
        // other's interior. Along d = nA × nB the part of A's triangle inside
        // B lies on the left (seen from outside A); whether an end starts or
        // ends the segment follows from which way its edge crosses.
        struct End {
            BoundedPoint point;
            bool starts;
        };
        End ends[2];
        int count = 0;
        auto edgeThrough = [&](const Vec3(&edge)[3], const int(&sides)[3], const Vec3(&tri)[3],
                               int k, bool edgeOfA) {
            const int k1 = (k + 1) % 3;
            if (sides[k] == sides[k1]) return true;
            const Vec3 &p = edge[k], &q = edge[k1];
            const int s0 = sideOf(p, q, tri[0], tri[1]), s1 = sideOf(p, q, tri[1], tri[2]),
                      s2 = sideOf(p, q, tri[2], tri[0]);
            if ((s0 > 0 || s1 > 0 || s2 > 0) && (s0 < 0 || s1 < 0 || s2 < 0)) return true;
            if (s0 == 0 || s1 == 0 || s2 == 0) return false;  // through an edge or corner
            if (count == 2) return false;
            // Constructed from the edge's lower point id, so both triangles
            // that share the edge get the same bits.
            const Side& own = edgeOfA ? sideA : sideB;
            const auto& t = edgeOfA ? ta : tb;
            const bool lowFirst = t[k] < t[k1];
            const BoundedPoint x = lowFirst ? crossingPoint(p, q, tri[0], tri[1], tri[2], origin)
                                            : crossingPoint(q, p, tri[0], tri[1], tri[2], origin);
            const bool outsideToInside = sides[k] > 0;
            ends[count++] = {x, edgeOfA ? !outsideToInside : outsideToInside};
            // Recorded once per (edge, triangle): from the edge's first
            // triangle.
            const std::uint32_t triangle = edgeOfA ? i : j;
            const std::uint32_t e = own.edgeOf[triangle][k];
            if (own.ownerOf[e] == triangle) {
                // Its error moves the volume through the fans at it: the
                // crossed triangle's (normal to it only: along the edge is
                // within the edge's own triangles' planes) and, by rounding,
                // those of the edge's triangles.
                const double crossed2 = (edgeOfA ? sideB : sideA).diameter2[edgeOfA ? j : i];
                out.bound.add(crossed2 / 3 * (x.offPlaneMm + x.roundingMm) +
                              2 * own.edgeDiameter2[e] / 3 * x.roundingMm);
                const Vec3 low = lowFirst ? p : q, high = lowFirst ? q : p;
                const Vec3 lowToHigh = high - low;
                const double span = dot(lowToHigh, lowToHigh);
                const double t01 = span > 0 ? dot(x.p + origin - low, lowToHigh) / span : 0;
                (edgeOfA ? out.crossingsA : out.crossingsB)
                    .push_back({e, t01, x, (lowFirst ? sides[k] : sides[k1]) > 0});
            }
            return true;
        };
        for (int k = 0; k < 3; ++k)
            if (!edgeThrough(pa, sa, pb, k, true) || !edgeThrough(pb, sb, pa, k, false)) {
                throw Degenerate{};
            }
        if (count == 0) return;
        if (count != 2 || ends[0].starts == ends[1].starts) {
            throw Degenerate{};
        }
        const BoundedPoint& start = ends[0].starts ? ends[0].point : ends[1].point;
        const BoundedPoint& end = ends[0].starts ? ends[1].point : ends[0].point;
        ++out.crossingPairs;
        // A's region runs along the segment from start to end, B's back.
        const Vec3 apexA = pa[0] - origin, apexB = pb[0] - origin;
        const double ls = length(start.p), le = length(end.p);
        out.volume.add(det(apexA, start.p, end.p) / 6);
        out.volume.add(det(apexB, end.p, start.p) / 6);
        // Both ends moving at once: the one term of second order.
        const double reach = std::sqrt(sideA.diameter2[i]) + std::sqrt(sideB.diameter2[j]);
        out.bound.add(reach * start.alongMm * end.alongMm / 6 +
                      2 * kEpsilon * (length(apexA) + length(apexB)) * ls * le / 6);
    };

    // The pair search in shares: A's boxes in slabs along x, each against
    // the boxes of B that reach into its slab, on the cores the process has
    // free. The shares are fixed whatever the cores, and their sums added in
    // order, so the result does not depend on how many ran.
    std::vector<std::uint32_t> byX(boxesA.size());
    std::iota(byX.begin(), byX.end(), 0u);
    std::stable_sort(byX.begin(), byX.end(), [&](std::uint32_t x, std::uint32_t y) {
        return boxesA[x].min_coord(0) < boxesA[y].min_coord(0);
    });
    const std::size_t shareCount = std::min<std::size_t>(kPairShares, boxesA.size());
    std::vector<PairShare> shares(shareCount);
    std::atomic<std::size_t> nextShare{0};
    std::atomic<bool> degenerate{false};
    // No triangle of one in the other's box: nothing crosses, no share.
    if (shareCount > 0)
        runOnFreeCores(shareCount - 1, [&](std::size_t, const std::atomic<bool>& stop) {
            std::vector<Box> mineA, mineB;
            for (std::size_t k; !stop && !degenerate && (k = nextShare++) < shareCount;) {
                const std::size_t first = k * byX.size() / shareCount,
                                  last = (k + 1) * byX.size() / shareCount;
                mineA.clear();
                double lo = INFINITY, hi = -INFINITY;
                for (std::size_t n = first; n < last; ++n) {
                    const Box& box = boxesA[byX[n]];
                    mineA.push_back(box);
                    lo = std::min(lo, box.min_coord(0));
                    hi = std::max(hi, box.max_coord(0));
                }
                mineB.clear();
                for (const Box& box : boxesB)
                    if (box.max_coord(0) >= lo && box.min_coord(0) <= hi) mineB.push_back(box);
                PairShare& share = shares[k];
                try {
                    CGAL::box_intersection_d(
                        mineA.begin(), mineA.end(), mineB.begin(), mineB.end(),
                        [&](const Box& boxA, const Box& boxB) { cut(share, boxA, boxB); });
                } catch (const Degenerate&) {
                    degenerate = true;
                }
            }
        });
    if (degenerate) return result;
    CompensatedSum volume, bound;
    for (PairShare& share : shares) {
        volume.add(share.volume.sum);
        volume.add(share.volume.carry);
        bound.add(share.bound.value());
        result.crossingPairs += share.crossingPairs;
        sideA.crossings.insert(sideA.crossings.end(), share.crossingsA.begin(),
                               share.crossingsA.end());
        sideB.crossings.insert(sideB.crossings.end(), share.crossingsB.begin(),
                               share.crossingsB.end());
    }

    sideA.sortCrossings();
    sideB.sortCrossings();
    if (!classifyPoints(sideA, sideB) || !classifyPoints(sideB, sideA)) return result;
    addEdgePieces(sideA, origin, volume, bound);
    addEdgePieces(sideB, origin, volume, bound);
    result.generalPosition = true;
    result.volumeMm3 = volume.value();
    result.boundMm3 = bound.value() + 4 * kEpsilon * std::abs(result.volumeMm3);
    return result;
}

}  // namespace dfrecon
