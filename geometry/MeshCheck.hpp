#pragma once
// Is a triangle mesh a valid closed surface? Every edge shared by exactly two
// triangles, every vertex's triangles one fan, consistent orientation, no
// self-intersections (triangle–triangle tests over a bounding volume
// hierarchy), plus the topology figures (components, Euler characteristic,
// genus) and enclosed volume. Works on a triangle soup so that broken input
// can be described rather than refused.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "geometry/SurfaceMeasures.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

/// Most self-intersecting pairs checkMesh counts before it stops looking:
/// one is enough for the verdict, and a million is enough to say where.
inline constexpr std::size_t kMaxCountedIntersections = 1'000'000;

struct MeshCheckReport {
    std::size_t vertices = 0;  // referenced by some triangle
    std::size_t triangles = 0;
    std::size_t edges = 0;
    std::size_t degenerateTriangles = 0;  // repeated vertex or zero area
    std::size_t boundaryEdges = 0;        // used by one triangle
    std::size_t nonManifoldEdges = 0;     // used by three or more
    std::size_t nonManifoldVertices = 0;  // triangles around it form several fans
    std::size_t misorientedEdges = 0;     // two triangles traverse it the same way
    std::size_t intersectingPairs = 0;    // pairs of triangles that cross or touch wrongly
    /// The search stopped at kMaxCountedIntersections pairs: there are at
    /// least intersectingPairs (a soup of coincident triangles has n²/2).
    bool intersectingPairsCapped = false;
    std::vector<std::pair<std::size_t, std::size_t>>
        intersectingExamples;  // the first ten, in order
    /// Every triangle that takes part in a defect: degenerate, on a
    /// boundary, non-manifold or misoriented edge, around a non-manifold
    /// vertex, or in an intersecting pair. Sorted, no repeats. Lets a caller
    /// find where a surface is broken (and rebuild just that part).
    std::vector<std::size_t> defectiveTriangles;
    std::size_t components = 0;
    long eulerCharacteristic = 0;  // V - E + F
    long genus = -1;               // total over components; -1 unless closed and manifold
    double volumeMm3 = 0;          // signed: > 0 when normals point outward
    double areaMm2 = 0;

    /// Closed, manifold and consistently oriented.
    bool watertight() const {
        return boundaryEdges == 0 && nonManifoldEdges == 0 && nonManifoldVertices == 0 &&
               misorientedEdges == 0 && degenerateTriangles == 0;
    }
    /// Watertight, free of self-intersections, and enclosing positive volume.
    bool validSolid() const { return watertight() && intersectingPairs == 0 && volumeMm3 > 0; }
};

/// Checks `soup`. The topology is judged from the triangles around each
/// vertex: O(T + V) memory (12 bytes a triangle and 12 a vertex, no list of
/// every edge use) and O(T log d) time for vertices of up to d triangles;
/// the self-intersection search visits only triangle pairs whose bounding
/// boxes overlap.
MeshCheckReport checkMesh(const TriangleSoup& soup);

/// What is known of a soup's pairs before a search: per triangle, 0
/// (nothing) or a group; the pairs of triangles in one nonzero group were
/// searched together and none collides, at the soup's present coordinates
/// (a strip checked as it was built, triangles that have not moved since a
/// clean check), so they are not tested again.
using CleanGroups = std::vector<std::uint32_t>;

/// checkMesh when some pairs are known clean (`cleanGroup`, one per
/// triangle): the same report, those pairs untested. O(T log T) plus the
/// pairs of overlapping boxes outside the groups.
MeshCheckReport checkMeshKnowing(const TriangleSoup& soup, const CleanGroups& cleanGroup);

/// checkMesh for a soup changed in a few places: the topology in full, but
/// only the pairs that involve one of `suspects` (triangle indices) searched
/// for intersections. The report is checkMesh's when no other pair
/// intersects, e.g. when every other pair was clean in a full check and
/// none of those triangles moved since (pieces rebuilt or swapped: their
/// new triangles are the suspects). O(T log T) for the topology, O(T) grid
/// look-ups for the pairs.
MeshCheckReport checkMeshNear(const TriangleSoup& soup, const std::vector<std::size_t>& suspects);

/// For a valid solid whose vertices moved but whose triangles stayed the
/// same (so its topology cannot have changed): the triangles that are now
/// degenerate or collide with another, found among those touching one of
/// `suspects` (every triangle with a moved vertex). Sorted, no repeats;
/// empty when the solid is still valid but for its volume's sign. O(T) box
/// tests plus grid look-ups around the suspects.
std::vector<std::size_t> defectsAfterMoving(const TriangleSoup& soup,
                                            const std::vector<std::size_t>& suspects);

/// Pairs of colliding triangles (i < j) a search found, and whether it
/// stopped at the most it was asked to count.
struct CollidingPairs {
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    bool capped = false;
};

/// A self-intersection search: given which triangles are degenerate (never
/// tested) and the most pairs to count, the colliding pairs.
using PairSearch =
    std::function<CollidingPairs(const std::vector<bool>& degenerate, std::size_t cap)>;

/// checkMesh with the self-intersection search left to `search`, for callers
/// that know where colliding pairs can lie (geometry/StackedMeshCheck). The
/// report is checkMesh's when `search` finds the pairs checkMesh's search
/// finds. O(T log T) plus the search.
MeshCheckReport checkMeshWith(const TriangleSoup& soup, const PairSearch& search);

/// The colliding pairs both of whose triangles are in `subset` (indices into
/// soup), at most `cap`, in a fixed order; as checkMesh judges pairs.
/// O(S log S + pairs of overlapping boxes) for S triangles in the subset,
/// plus O(points) to map them. Pairs within one of `cleanGroup`'s groups
/// (if given; indexed like soup's triangles) are not tested.
CollidingPairs collidingPairsAmong(const TriangleSoup& soup, const std::vector<bool>& degenerate,
                                   const std::vector<std::size_t>& subset, std::size_t cap,
                                   const CleanGroups* cleanGroup = nullptr);

/// The self-intersecting pairs checkMesh would count, without the topology
/// checks (e.g. for a piece of surface, which has a boundary).
std::size_t countSelfIntersections(const TriangleSoup& soup);

/// The pairs of triangles countSelfIntersections counts (indices, i < j).
std::vector<std::pair<std::size_t, std::size_t>> selfIntersectingPairs(const TriangleSoup& soup);

/// Do two triangles share a point? Exposed for tests. Triangles sharing
/// vertices (by index) are handled by checkMesh; this is the plain test.
bool trianglesIntersect(const Vec3 a[3], const Vec3 b[3]);

/// Has triangle t of `soup` a repeated vertex or no area (as checkMesh
/// counts degenerate triangles)? O(1).
bool isDegenerate(const TriangleSoup& soup, const std::array<std::uint32_t, 3>& t);
/// Do triangles s and t of `soup` (both non-degenerate) meet where they
/// should not, as checkMesh judges a pair? O(1).
bool trianglesCollide(const TriangleSoup& soup, const std::array<std::uint32_t, 3>& s,
                      const std::array<std::uint32_t, 3>& t);
/// Do triangles s (corners a) and t (corners b), given by vertex ids, meet
/// where they should not? Shared vertices are allowed contact: sharing an
/// edge they collide only when folded onto each other, sharing one vertex
/// only when they overlap beyond it. Both must be non-degenerate.
bool trianglesCollide(const std::array<std::uint32_t, 3>& s, const Vec3 a[3],
                      const std::array<std::uint32_t, 3>& t, const Vec3 b[3]);

}  // namespace dfrecon
