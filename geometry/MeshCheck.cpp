#include "geometry/MeshCheck.hpp"

#include "geometry/BoxGrid.hpp"
#include "geometry/CoreBudget.hpp"
#include "geometry/Polygon.hpp"
#include "geometry/TriangleBvh.hpp"
#include "geometry/UnionFind.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>

namespace dfrecon {

using Triangle = std::array<std::uint32_t, 3>;

namespace {

// Orientations within this fraction of the product of the edge lengths
// (angles below about 1e-10 rad) count as zero. Reconstructed surfaces are
// full of configurations that are exactly coplanar or collinear in exact
// arithmetic (strips between straight contour runs, vertical walls, slices
// repeating the same outline) but only nearly so in doubles, where the plain
// determinant's sign is noise.
constexpr double kDegenerate = 1e-10;

// The plane of triangle abc, for orientation tests of several points
// against it: what orient() computes per point, computed once.
struct OrientPlane {
    Vec3 a, normal;  // normal: (b - a) x (c - a)
    double scale;    // kDegenerate² |b - a|² |c - a|², as orient() multiplies it
    OrientPlane(Vec3 a_, Vec3 b, Vec3 c) : a(a_) {
        const Vec3 u = b - a, v = c - a;
        normal = cross(u, v);
        scale = kDegenerate * kDegenerate * dot(u, u) * dot(v, v);
    }
    // Signed volume (×6) of tetrahedron abcd: > 0 when d is above abc, 0
    // when d is within the tolerance of the plane. Compared squared (no
    // square roots: this is the checker's innermost test).
    double orient(Vec3 d) const {
        const Vec3 w = d - a;
        const double det = dot(normal, w);
        return det * det <= scale * dot(w, w) ? 0.0 : det;
    }
};

// OrientPlane(a, b, c).orient(d): the same value, bit for bit.
double orient(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    return OrientPlane(a, b, c).orient(d);
}

// 2D orientation in the plane that drops `axis`.
double orient2(Vec3 a, Vec3 b, Vec3 c, int axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const double bu = b[u] - a[u], bv = b[v] - a[v], cu = c[u] - a[u], cv = c[v] - a[v];
    const double det = bu * cv - bv * cu;
    return det * det <= kDegenerate * kDegenerate * (bu * bu + bv * bv) * (cu * cu + cv * cv) ? 0.0
                                                                                              : det;
}

// p in the plane that drops `axis`.
Point2 project(Vec3 p, int axis) {
    return {p[(axis + 1) % 3], p[(axis + 2) % 3]};
}

// Closed 2D segment intersection in the plane dropping `axis`.
bool segmentsMeet2(Vec3 p, Vec3 q, Vec3 a, Vec3 b, int axis) {
    return segmentContact(project(p, axis), project(q, axis), project(a, axis), project(b, axis)) !=
           SegmentContact::None;
}

// Closed point-in-triangle in the plane dropping `axis`.
bool insideTriangle2(Vec3 p, const Vec3 t[3], int axis) {
    const double d0 = orient2(t[0], t[1], p, axis), d1 = orient2(t[1], t[2], p, axis),
                 d2 = orient2(t[2], t[0], p, axis);
    return (d0 >= 0 && d1 >= 0 && d2 >= 0) || (d0 <= 0 && d1 <= 0 && d2 <= 0);
}

int dominantAxis(Vec3 n) {
    const double x = std::abs(n.x), y = std::abs(n.y), z = std::abs(n.z);
    return x >= y && x >= z ? 0 : (y >= z ? 1 : 2);
}

bool coplanarTrianglesMeet(const Vec3 a[3], const Vec3 b[3], int axis) {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (segmentsMeet2(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3], axis)) return true;
    return insideTriangle2(a[0], b, axis) || insideTriangle2(b[0], a, axis);
}

// Does the closed segment pq meet the closed triangle t (non-degenerate)?
// `plane` is t's (OrientPlane(t[0], t[1], t[2])), dp and dq its orient() of
// p and q: trianglesIntersect has them already for all six edges it tests.
bool segmentMeetsTriangle(Vec3 p, Vec3 q, double dp, double dq, const OrientPlane& plane,
                          const Vec3 t[3]) {
    if ((dp > 0 && dq > 0) || (dp < 0 && dq < 0)) return false;
    if (dp == 0 && dq == 0) {
        const int axis = dominantAxis(plane.normal);
        return insideTriangle2(p, t, axis) || insideTriangle2(q, t, axis) ||
               segmentsMeet2(p, q, t[0], t[1], axis) || segmentsMeet2(p, q, t[1], t[2], axis) ||
               segmentsMeet2(p, q, t[2], t[0], axis);
    }
    // The line pq passes inside iff it turns the same way around all edges.
    const double s0 = orient(p, q, t[0], t[1]), s1 = orient(p, q, t[1], t[2]),
                 s2 = orient(p, q, t[2], t[0]);
    if ((s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0)) return true;
    if (!((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0))) return false;
    // Zeros: on an edge of t, or a segment lying almost in t's plane, where
    // the orientations are noise (a wall's triangle beside another of the
    // same wall). Where the segment meets the plane decides.
    const Vec3 x = p + (dp / (dp - dq)) * (q - p);
    return insideTriangle2(x, t, dominantAxis(plane.normal));
}

}  // namespace

bool isDegenerate(const TriangleSoup& soup, const Triangle& t) {
    const Vec3 p0 = soup.points[t[0]], p1 = soup.points[t[1]], p2 = soup.points[t[2]];
    return t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || length(cross(p1 - p0, p2 - p0)) == 0;
}

bool trianglesCollide(const TriangleSoup& soup, const Triangle& s, const Triangle& t) {
    Vec3 a[3], b[3];
    for (int k = 0; k < 3; ++k) {
        a[k] = soup.points[s[std::size_t(k)]];
        b[k] = soup.points[t[std::size_t(k)]];
    }
    return trianglesCollide(s, a, t, b);
}

namespace {

// trianglesCollide as seen from s: where the triangles share vertices its
// side and wedge tests are in floating point, taken in s's frame, and a
// fold within a rounding error of flat can come out either way.
bool collidesSeenFrom(const std::array<std::uint32_t, 3>& s, const Vec3 a[3],
                      const std::array<std::uint32_t, 3>& t, const Vec3 b[3]) {
    int shared = 0, sa[3] = {-1, -1, -1};  // sa[k]: index in t of s[k], or -1
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (s[std::size_t(i)] == t[std::size_t(j)]) {
                sa[i] = j;
                ++shared;
            }
    if (shared == 0) return trianglesIntersect(a, b);
    if (shared == 3) return true;  // the same triangle twice
    const Vec3 normal = cross(a[1] - a[0], a[2] - a[0]);
    if (shared == 2) {
        int oa = 0, ob = 0;
        while (sa[oa] >= 0) ++oa;  // s's vertex off the shared edge
        while (ob == sa[0] || ob == sa[1] || ob == sa[2]) ++ob;
        const Vec3 u = a[(oa + 1) % 3], v = a[(oa + 2) % 3];
        if (orient(u, v, a[oa], b[ob]) != 0)
            return false;  // different planes: meet on the edge only
        // Coplanar: folded onto each other when both lie on the same side.
        const double sideA = dot(cross(v - u, a[oa] - u), normal);
        const double sideB = dot(cross(v - u, b[ob] - u), normal);
        return sideA * sideB > 0;
    }
    // One shared vertex: compare what lies opposite it.
    int ka = 0;
    while (sa[ka] < 0) ++ka;
    const int kb = sa[ka];
    const Vec3 a1 = a[(ka + 1) % 3], a2 = a[(ka + 2) % 3], b1 = b[(kb + 1) % 3],
               b2 = b[(kb + 2) % 3];
    const Vec3 v = a[ka];
    const OrientPlane planeA(v, a1, a2);
    const Vec3 nA = planeA.normal, nB = cross(b1 - v, b2 - v);
    if (planeA.orient(b1) == 0 && planeA.orient(b2) == 0) {
        // Coplanar wedges at v overlap iff a direction of one lies strictly
        // inside the other, or they coincide.
        const int axis = dominantAxis(normal);
        auto strictlyInside = [&](Vec3 x, Vec3 p, Vec3 q) {
            const double w = orient2(v, p, q, axis);
            return orient2(v, p, x, axis) * w > 0 && orient2(v, x, q, axis) * w > 0;
        };
        auto sameDirection = [&](Vec3 x, Vec3 y) {
            return orient2(v, x, y, axis) == 0 && dot(x - v, y - v) > 0;
        };
        return strictlyInside(b1, a1, a2) || strictlyInside(b2, a1, a2) ||
               strictlyInside(a1, b1, b2) || strictlyInside(a2, b1, b2) ||
               (sameDirection(a1, b1) && sameDirection(a2, b2)) ||
               (sameDirection(a1, b2) && sameDirection(a2, b1));
    }
    // Different planes: both triangles meet their planes' common line in a
    // segment starting at v; they overlap beyond v iff one direction of that
    // line points into both wedges.
    const Vec3 line = cross(nA, nB);
    auto intoWedge = [&](Vec3 d, Vec3 p, Vec3 q, Vec3 n) {
        return dot(cross(p - v, d), n) > 0 && dot(cross(d, q - v), n) > 0;
    };
    for (const Vec3 d : {line, -1.0 * line})
        if (intoWedge(d, a1, a2, nA) && intoWedge(d, b1, b2, nB)) return true;
    return false;
}

}  // namespace

bool trianglesCollide(const std::array<std::uint32_t, 3>& s, const Vec3 a[3],
                      const std::array<std::uint32_t, 3>& t, const Vec3 b[3]) {
    // Judged from both sides where they share a vertex, so that a pair's
    // verdict does not depend on which comes first: checkMesh's hierarchy
    // and the local checks after moving vertices (defectsAfterMoving) meet
    // a pair in either order, and once disagreed on a fold a micrometre from
    // flat (hostile label stacks moved apart, seeds 117 and 166).
    const bool sharesVertex = s[0] == t[0] || s[0] == t[1] || s[0] == t[2] || s[1] == t[0] ||
                              s[1] == t[1] || s[1] == t[2] || s[2] == t[0] || s[2] == t[1] ||
                              s[2] == t[2];
    return collidesSeenFrom(s, a, t, b) || (sharesVertex && collidesSeenFrom(t, b, s, a));
}

namespace {

using TrianglePair = std::pair<std::size_t, std::size_t>;

// Soups smaller than this are searched on the calling thread: starting
// threads costs more than a small search (a piece of a slab, a strip).
constexpr std::size_t kParallelFromTriangles = 20000;
// Node pairs the search is cut into, whatever the thread count, so that
// which pairs a capped search finds does not depend on the machine.
constexpr std::size_t kSearchTasks = 256;

// The pairs (i < j) of non-degenerate triangles that collide, at most
// `cap`: the first `cap` in a fixed order (TriangleBvh::selfPairTasks', then
// each task's). `capped` says whether the search stopped there. Large soups
// are searched on every core left free, tasks taken in order, each run to its end or
// its own cap, and no task started once `cap` pairs are in: the tasks done
// are a prefix that holds the first `cap`. O(T log T + pairs of overlapping
// boxes) work. Pairs within one clean group (cleanGroup, if given:
// CleanGroups) are not tested.
std::vector<TrianglePair> collidingPairs(const TriangleSoup& soup,
                                         const std::vector<bool>& degenerate, std::size_t cap,
                                         bool& capped, const CleanGroups* cleanGroup = nullptr) {
    const TriangleBvh bvh(soup, BvhSplit::Halving, BvhQueries::PairsOnly);
    const std::vector<TriangleBvh::NodePair> tasks = bvh.selfPairTasks(kSearchTasks);
    // Subtrees of one clean group (a strip searched as it was built) hold
    // only pairs that are not tested: not entered at all, where the search
    // would walk down to every pair of neighbours in the strip to skip it.
    const std::vector<std::uint32_t> nodeGroup =
        cleanGroup ? bvh.nodeGroups(*cleanGroup) : std::vector<std::uint32_t>();
    auto withinOneGroup = [&](int a, int b) {
        if (nodeGroup.empty()) return false;
        const std::uint32_t g = nodeGroup[std::size_t(a)];
        return g != 0 && g == nodeGroup[std::size_t(b)];
    };
    std::vector<std::vector<TrianglePair>> found(tasks.size());
    struct TaskFull {};  // thrown to leave a task at the cap
    auto runTask = [&](std::size_t k) {
        try {
            bvh.selfPairsUnder(
                tasks[k],
                [&](std::size_t i, std::size_t j) {
                    if (degenerate[i] || degenerate[j]) return;
                    if (cleanGroup && (*cleanGroup)[i] != 0 && (*cleanGroup)[i] == (*cleanGroup)[j])
                        return;
                    if (!trianglesCollide(soup, soup.triangles[i], soup.triangles[j])) return;
                    found[k].emplace_back(std::min(i, j), std::max(i, j));
                    if (found[k].size() == cap) throw TaskFull{};
                },
                withinOneGroup);
        } catch (const TaskFull&) {
        }
        return found[k].size();
    };
    // Only the cores no other work holds (geometry/CoreBudget): ROIs
    // reconstructed in parallel each hold one already.
    std::atomic<std::size_t> next{0}, total{0};
    runOnFreeCores(soup.triangles.size() < kParallelFromTriangles ? 0 : helpersFor(tasks.size(), 2),
                   [&](std::size_t, const std::atomic<bool>& stop) {
                       for (std::size_t k; !stop && total < cap && (k = next++) < tasks.size();)
                           total += runTask(k);
                   });
    std::vector<TrianglePair> pairs;
    for (const std::vector<TrianglePair>& part : found) {
        pairs.insert(pairs.end(), part.begin(), part.end());
        if (pairs.size() >= cap) break;
    }
    capped = pairs.size() >= cap;
    if (capped) pairs.resize(cap);
    return pairs;
}

}  // namespace

std::vector<std::pair<std::size_t, std::size_t>> selfIntersectingPairs(const TriangleSoup& soup) {
    std::vector<bool> degenerate(soup.triangles.size());
    for (std::size_t t = 0; t < soup.triangles.size(); ++t)
        degenerate[t] = isDegenerate(soup, soup.triangles[t]);
    bool capped = false;
    return collidingPairs(soup, degenerate, SIZE_MAX, capped);
}

std::size_t countSelfIntersections(const TriangleSoup& soup) {
    return selfIntersectingPairs(soup).size();
}

bool trianglesIntersect(const Vec3 a[3], const Vec3 b[3]) {
    const OrientPlane planeB(b[0], b[1], b[2]);
    const double da[3] = {planeB.orient(a[0]), planeB.orient(a[1]), planeB.orient(a[2])};
    if ((da[0] > 0 && da[1] > 0 && da[2] > 0) || (da[0] < 0 && da[1] < 0 && da[2] < 0))
        return false;
    const OrientPlane planeA(a[0], a[1], a[2]);
    const double db[3] = {planeA.orient(b[0]), planeA.orient(b[1]), planeA.orient(b[2])};
    if ((db[0] > 0 && db[1] > 0 && db[2] > 0) || (db[0] < 0 && db[1] < 0 && db[2] < 0))
        return false;
    if (da[0] == 0 && da[1] == 0 && da[2] == 0)
        return coplanarTrianglesMeet(a, b, dominantAxis(planeB.normal));
    // The intersection, if any, is a segment whose ends lie on edges.
    for (int k = 0; k < 3; ++k)
        if (segmentMeetsTriangle(a[k], a[(k + 1) % 3], da[k], da[(k + 1) % 3], planeB, b) ||
            segmentMeetsTriangle(b[k], b[(k + 1) % 3], db[k], db[(k + 1) % 3], planeA, a))
            return true;
    return false;
}

namespace {

// The colliding pairs (i < j) that involve a suspect, at most `cap`, in a
// fixed order (suspects in the order given, then the grid's). Each pair is
// tested once. O(T) box look-ups on a grid over the suspects' boxes, plus
// the tests.
std::vector<TrianglePair> collidingPairsNear(const TriangleSoup& soup,
                                             const std::vector<bool>& degenerate,
                                             const std::vector<std::size_t>& suspects,
                                             std::size_t cap, bool& capped) {
    capped = false;
    std::vector<TrianglePair> pairs;
    if (suspects.empty()) return pairs;
    std::vector<bool> suspect(soup.triangles.size(), false);
    std::vector<Box3> boxes;
    Box3 scene;
    for (std::size_t s : suspects) {
        suspect[s] = true;
        Box3& box = boxes.emplace_back();
        for (std::uint32_t v : soup.triangles[s]) box.add(soup.points[v]);
        scene.add(box);
    }
    const BoxGrid grid = BoxGrid::sizedToBoxes(std::move(boxes));
    for (std::size_t t = 0; t < soup.triangles.size() && pairs.size() < cap; ++t) {
        if (degenerate[t]) continue;
        Box3 box;
        for (std::uint32_t v : soup.triangles[t]) box.add(soup.points[v]);
        if (!box.overlaps(scene)) continue;
        grid.overlapping(box, [&](std::uint32_t k) {
            const std::size_t s = suspects[k];
            // A pair of two suspects is tested from its larger index only.
            if (s == t || degenerate[s] || (suspect[t] && t < s) || pairs.size() >= cap) return;
            if (trianglesCollide(soup, soup.triangles[s], soup.triangles[t]))
                pairs.emplace_back(std::min(s, t), std::max(s, t));
        });
    }
    capped = pairs.size() >= cap;
    return pairs;
}

}  // namespace

namespace {

// checkMesh, its intersection search left to `search`.
MeshCheckReport checkSoup(const TriangleSoup& soup, const PairSearch& search) {
    MeshCheckReport report;
    report.triangles = soup.triangles.size();
    const std::size_t n = soup.points.size();

    if (soup.triangles.size() >= (std::size_t(1) << 31))
        throw std::length_error("checkMesh: 2^31 triangles or more");
    std::vector<bool> used(n, false), degenerate(soup.triangles.size(), false);
    const SurfaceMeasures measures = measureSurface(soup);
    report.volumeMm3 = measures.volumeMm3;
    report.areaMm2 = measures.areaMm2;
    for (std::uint32_t t = 0; t < soup.triangles.size(); ++t) {
        const Triangle& tri = soup.triangles[t];
        if (isDegenerate(soup, tri)) {
            degenerate[t] = true;
            ++report.degenerateTriangles;
            report.defectiveTriangles.push_back(t);
        }
        for (std::uint32_t v : tri) used[v] = true;
    }
    // The triangles around each vertex, packed (around[first[v] .. first[v + 1]));
    // a triangle with a vertex twice is listed twice, next to itself.
    std::vector<std::uint32_t> first(n + 1, 0), around(3 * soup.triangles.size());
    for (const Triangle& tri : soup.triangles)
        for (std::uint32_t v : tri) ++first[v + 1];
    std::partial_sum(first.begin(), first.end(), first.begin());
    {
        std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
        for (std::uint32_t t = 0; t < soup.triangles.size(); ++t)
            for (std::uint32_t v : soup.triangles[t]) around[fill[v]++] = t;
    }
    // Each edge is judged at its lower vertex, from the triangles around it:
    // its uses (the other vertex, then triangle << 1 | (it runs from lower to
    // higher)) sorted, so each edge's uses are adjacent. One vertex's list
    // at a time, not one list of every edge use (12 bytes each: the largest
    // block of a large check, 8.4 M uses on a 2.8 M-triangle surface).
    struct EdgeUse {
        std::uint32_t hi;
        std::uint32_t triangleAndForward;
        std::uint32_t triangle() const { return triangleAndForward >> 1; }
        bool forward() const { return (triangleAndForward & 1) != 0; }
        bool operator<(const EdgeUse& o) const {
            return hi != o.hi ? hi < o.hi : triangleAndForward < o.triangleAndForward;
        }
    };
    std::vector<EdgeUse> uses;
    // Reused from vertex to vertex: (other vertex, position in the ring) of
    // each edge at v, and the groups of the ring's triangles.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> spokes;
    UnionFind parts(n), fan;
    for (std::size_t v = 0; v < n; ++v) {
        if (!used[v]) continue;
        ++report.vertices;
        const std::uint32_t* ring = around.data() + first[v];
        const std::size_t k = first[v + 1] - first[v];
        uses.clear();
        for (std::size_t p = 0; p < k; ++p) {
            if (p > 0 && ring[p] == ring[p - 1]) continue;  // the same triangle again
            const std::uint32_t t = ring[p];
            const Triangle& tri = soup.triangles[t];
            for (std::size_t e = 0; e < 3; ++e) {
                const std::uint32_t a = tri[e], b = tri[(e + 1) % 3];
                if (a != b && std::min(a, b) == v)
                    uses.push_back({std::max(a, b), t << 1 | (a < b ? 1u : 0u)});
            }
        }
        std::sort(uses.begin(), uses.end());
        for (std::size_t begin = 0; begin < uses.size();) {
            std::size_t end = begin;
            while (end < uses.size() && uses[end].hi == uses[begin].hi) ++end;
            ++report.edges;
            const std::size_t count = end - begin;
            bool defective = false;
            if (count == 1) ++report.boundaryEdges, defective = true;
            if (count > 2) ++report.nonManifoldEdges, defective = true;
            if (count == 2 && uses[begin].forward() == uses[begin + 1].forward())
                ++report.misorientedEdges, defective = true;
            if (defective)
                for (std::size_t u = begin; u < end; ++u)
                    report.defectiveTriangles.push_back(uses[u].triangle());
            parts.join(v, uses[begin].hi);
            begin = end;
        }
        // The triangles around v must form one fan: join those sharing an
        // edge at v and count the groups. By sorting the edges, not comparing
        // every pair: a hostile file put ten million triangles at one vertex.
        spokes.clear();
        for (std::size_t p = 0; p < k; ++p)
            for (std::uint32_t x : soup.triangles[ring[p]])
                if (x != v) spokes.emplace_back(x, std::uint32_t(p));
        std::sort(spokes.begin(), spokes.end());
        fan.reset(k);
        for (std::size_t s = 1; s < spokes.size(); ++s)
            if (spokes[s].first == spokes[s - 1].first)
                fan.join(spokes[s].second, spokes[s - 1].second);
        std::size_t groups = 0;
        for (std::size_t p = 0; p < k && groups < 2; ++p) groups += fan.find(p) == p;
        if (groups > 1) {
            ++report.nonManifoldVertices;
            report.defectiveTriangles.insert(report.defectiveTriangles.end(), ring, ring + k);
        }
    }
    // Freed before the pair search's hierarchy is built.
    decltype(first)().swap(first);
    decltype(around)().swap(around);
    for (std::size_t v = 0; v < n; ++v) report.components += used[v] && parts.find(v) == v;
    report.eulerCharacteristic =
        long(report.vertices) - long(report.edges) + long(report.triangles);
    if (report.watertight())
        report.genus = (2 * long(report.components) - report.eulerCharacteristic) / 2;

    CollidingPairs found = search(degenerate, kMaxCountedIntersections);
    std::vector<TrianglePair>& pairs = found.pairs;
    report.intersectingPairs = pairs.size();
    report.intersectingPairsCapped = found.capped;
    for (const auto& [i, j] : pairs) {
        report.defectiveTriangles.push_back(i);
        report.defectiveTriangles.push_back(j);
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.resize(std::min<std::size_t>(pairs.size(), 10));
    report.intersectingExamples = std::move(pairs);
    std::vector<std::size_t>& defective = report.defectiveTriangles;
    std::sort(defective.begin(), defective.end());
    defective.erase(std::unique(defective.begin(), defective.end()), defective.end());
    return report;
}

}  // namespace

MeshCheckReport checkMesh(const TriangleSoup& soup) {
    return checkSoup(soup, [&](const std::vector<bool>& degenerate, std::size_t cap) {
        CollidingPairs found;
        found.pairs = collidingPairs(soup, degenerate, cap, found.capped);
        return found;
    });
}

MeshCheckReport checkMeshKnowing(const TriangleSoup& soup, const CleanGroups& cleanGroup) {
    return checkSoup(soup, [&](const std::vector<bool>& degenerate, std::size_t cap) {
        CollidingPairs found;
        found.pairs = collidingPairs(soup, degenerate, cap, found.capped, &cleanGroup);
        return found;
    });
}

MeshCheckReport checkMeshNear(const TriangleSoup& soup, const std::vector<std::size_t>& suspects) {
    return checkSoup(soup, [&](const std::vector<bool>& degenerate, std::size_t cap) {
        CollidingPairs found;
        found.pairs = collidingPairsNear(soup, degenerate, suspects, cap, found.capped);
        return found;
    });
}

std::vector<std::size_t> defectsAfterMoving(const TriangleSoup& soup,
                                            const std::vector<std::size_t>& suspects) {
    std::vector<bool> degenerate(soup.triangles.size(), false);
    std::vector<std::size_t> defects;
    for (const std::size_t t : suspects)
        if ((degenerate[t] = isDegenerate(soup, soup.triangles[t]))) defects.push_back(t);
    bool capped = false;
    for (const TrianglePair& pair :
         collidingPairsNear(soup, degenerate, suspects, kMaxCountedIntersections, capped)) {
        defects.push_back(pair.first);
        defects.push_back(pair.second);
    }
    std::sort(defects.begin(), defects.end());
    defects.erase(std::unique(defects.begin(), defects.end()), defects.end());
    return defects;
}

MeshCheckReport checkMeshWith(const TriangleSoup& soup, const PairSearch& search) {
    return checkSoup(soup, search);
}

CollidingPairs collidingPairsAmong(const TriangleSoup& soup, const std::vector<bool>& degenerate,
                                   const std::vector<std::size_t>& subset, std::size_t cap,
                                   const CleanGroups* cleanGroup) {
    // The subset as a soup of its own (the hierarchy is built over a whole
    // soup); shared vertices stay shared.
    const TriangleSoup part = soupOfTriangles(soup, subset);
    std::vector<bool> partDegenerate;
    partDegenerate.reserve(subset.size());
    CleanGroups partGroup;
    if (cleanGroup) partGroup.reserve(subset.size());
    for (std::size_t t : subset) {
        partDegenerate.push_back(degenerate[t]);
        if (cleanGroup) partGroup.push_back((*cleanGroup)[t]);
    }
    CollidingPairs found;
    found.pairs =
        collidingPairs(part, partDegenerate, cap, found.capped, cleanGroup ? &partGroup : nullptr);
    for (auto& [i, j] : found.pairs) {
        i = subset[i];
        j = subset[j];
        if (i > j) std::swap(i, j);
    }
    return found;
}

}  // namespace dfrecon
