#include "geometry/StackedMeshCheck.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <optional>

#include "geometry/ContourValidation.hpp"
#include "geometry/CoreBudget.hpp"

namespace dfrecon {

namespace {

constexpr std::uint32_t kNone = UINT32_MAX;

// Where the loops' vertices are: the plane of each (kNone: on none) and the
// next vertex along its loop, so that an edge (u, v) is a loop edge iff
// next[u] == v or next[v] == u.
struct LoopVertices {
    std::vector<std::uint32_t> plane, next;
};

// The loops' vertices, or nothing when a loop is too short, a vertex is in
// two loops or off its plane's height, or two neighbours coincide.
std::optional<LoopVertices> loopVertices(const TriangleSoup& soup, const PieceStack& stack) {
    LoopVertices at{std::vector<std::uint32_t>(soup.points.size(), kNone),
                    std::vector<std::uint32_t>(soup.points.size(), kNone)};
    for (std::size_t k = 0; k < stack.planeLoops.size(); ++k)
        for (const std::vector<std::uint32_t>& loop : stack.planeLoops[k]) {
            if (loop.size() < 3) return std::nullopt;
            for (std::size_t i = 0; i < loop.size(); ++i) {
                const std::uint32_t v = loop[i], w = loop[(i + 1) % loop.size()];
                if (v >= soup.points.size() || at.plane[v] != kNone) return std::nullopt;
                if (soup.points[v].z != stack.planeZMm[k]) return std::nullopt;
                if (soup.points[v] == soup.points[w]) return std::nullopt;
                at.plane[v] = std::uint32_t(k);
                at.next[v] = w;
            }
        }
    return at;
}

// Are the loops of plane k, at the soup's coordinates, simple and pairwise
// apart (no shared point at all, unlike contours of one slice, which may
// touch)?
bool loopsApart(const TriangleSoup& soup, const std::vector<std::vector<std::uint32_t>>& loops) {
    std::vector<Polygon> polygons;
    for (const std::vector<std::uint32_t>& loop : loops) {
        Polygon& p = polygons.emplace_back();
        for (std::uint32_t v : loop) p.push_back({soup.points[v].x, soup.points[v].y});
    }
    return !findContourDefect(polygons) && countContourContacts(polygons, 0) == 0;
}

// Does triangle `tri` meet plane k (height z) only in a loop vertex or a
// loop edge of that plane?
bool meetsPlaneInLoop(const TriangleSoup& soup, const std::array<std::uint32_t, 3>& tri,
                      std::uint32_t k, double z, const LoopVertices& at) {
    std::uint32_t on[3];
    int count = 0;
    for (std::uint32_t v : tri)
        if (soup.points[v].z == z) {
            if (at.plane[v] != k) return false;
            on[count++] = v;
        }
    if (count == 3) return false;  // lying in the plane
    return count < 2 || at.next[on[0]] == on[1] || at.next[on[1]] == on[0];
}

}  // namespace

bool stackSeparatesPieces(const TriangleSoup& soup, const std::vector<std::uint32_t>& pieceOf,
                          const PieceStack& stack) {
    const std::vector<double>& z = stack.planeZMm;
    if (pieceOf.size() != soup.triangles.size() || stack.planeLoops.size() != z.size())
        return false;
    for (std::size_t k = 0; k < z.size(); ++k)
        if (!std::isfinite(z[k]) || (k > 0 && !(z[k - 1] < z[k]))) return false;
    const std::optional<LoopVertices> at = loopVertices(soup, stack);
    if (!at) return false;
    // Every piece between its planes, touching them only in their loops:
    // then two triangles of different pieces can share only points of one
    // plane's loops, which they share as vertices and edges.
    for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
        const std::uint32_t p = pieceOf[t];
        if (p > z.size()) return false;
        const double lo = p == 0 ? -INFINITY : z[p - 1];
        const double hi = p == z.size() ? INFINITY : z[p];
        for (std::uint32_t v : soup.triangles[t]) {
            const double height = soup.points[v].z;
            if (!(height >= lo && height <= hi)) return false;
        }
        if (p > 0 && !meetsPlaneInLoop(soup, soup.triangles[t], p - 1, lo, *at)) return false;
        if (p < z.size() && !meetsPlaneInLoop(soup, soup.triangles[t], p, hi, *at)) return false;
    }
    // Loops that touch or cross would let triangles of both sides meet
    // beyond the vertices and edges they share.
    return stack.loopsKnownApart || planeLoopsApart(soup, stack);
}

bool planeLoopsApart(const TriangleSoup& soup, const PieceStack& stack) {
    for (const std::vector<std::vector<std::uint32_t>>& loops : stack.planeLoops)
        if (!loopsApart(soup, loops)) return false;
    return true;
}

namespace {

// The colliding pairs within each piece that `stack` says is not searched
// yet, pieces in order, at most `cap` in all. Pieces run on the cores left
// free, taken in order, none started once `cap` pairs are in: the pieces
// done are a prefix that holds the first `cap`.
CollidingPairs pairsWithinPieces(const TriangleSoup& soup,
                                 const std::vector<std::uint32_t>& pieceOf, const PieceStack& stack,
                                 const std::vector<bool>& degenerate, std::size_t cap) {
    const std::size_t pieceCount = stack.planeZMm.size() + 1;
    std::vector<std::vector<std::size_t>> members(pieceCount);
    std::size_t searchedTriangles = 0;
    for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
        const std::uint32_t p = pieceOf[t];
        if (p < stack.searched.size() && stack.searched[p]) continue;
        members[p].push_back(t);
        ++searchedTriangles;
    }
    const CleanGroups* clean = stack.cleanGroup.empty() ? nullptr : &stack.cleanGroup;
    std::vector<CollidingPairs> found(pieceCount);
    std::atomic<std::size_t> next{0}, total{0};
    // Small surfaces on the calling thread, as checkMesh does.
    runOnFreeCores(searchedTriangles < 20000 ? 0 : helpersFor(pieceCount, 2),
                   [&](std::size_t, const std::atomic<bool>& stop) {
                       for (std::size_t p; !stop && total < cap && (p = next++) < pieceCount;) {
                           if (members[p].size() < 2) continue;
                           found[p] = collidingPairsAmong(soup, degenerate, members[p], cap, clean);
                           total += found[p].pairs.size();
                       }
                   });
    CollidingPairs all;
    for (CollidingPairs& part : found) {
        all.pairs.insert(all.pairs.end(), part.pairs.begin(), part.pairs.end());
        if (all.pairs.size() >= cap) break;
    }
    all.capped = all.pairs.size() >= cap;
    if (all.capped) all.pairs.resize(cap);
    return all;
}

}  // namespace

MeshCheckReport checkStackedMesh(const TriangleSoup& soup,
                                 const std::vector<std::uint32_t>& pieceOf,
                                 const PieceStack& stack) {
    if (!stackSeparatesPieces(soup, pieceOf, stack))
        return stack.cleanGroup.empty() ? checkMesh(soup)
                                        : checkMeshKnowing(soup, stack.cleanGroup);
    return checkMeshWith(soup, [&](const std::vector<bool>& degenerate, std::size_t cap) {
        return pairsWithinPieces(soup, pieceOf, stack, degenerate, cap);
    });
}

}  // namespace dfrecon
