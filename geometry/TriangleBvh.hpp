#pragma once
// A bounding volume hierarchy over the triangles of a soup: splits by the
// surface area heuristic (binned), leaves of up to 4 triangles. Answers the two
// queries dfrecon needs: pairs of triangles whose boxes overlap (self-
// intersection checks) and the nearest triangle to a point (exact distances
// for verifiers and benchmarks).
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "geometry/Box3.hpp"
#include "geometry/ClosestPoint.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

/// How a TriangleBvh splits its nodes. The surface area heuristic makes
/// nearest-point searches visit fewer boxes; halving by count builds about
/// twice as fast and serves pair searches (self-intersection checks, which
/// look at every overlapping pair either way) as well.
enum class BvhSplit { SurfaceArea, Halving };

/// Which queries a TriangleBvh answers. The nearest search keeps its own
/// copy of every triangle's corners and a ball around each (about 110 bytes
/// a triangle, a sixth of a self-intersection check's time on large
/// meshes); a hierarchy only for pairs goes without.
enum class BvhQueries { All, PairsOnly };

class TriangleBvh {
  public:
    /// Builds over `soup`, which must outlive the hierarchy. O(T log T).
    /// With BvhQueries::PairsOnly, nearest() and nearestWithin() throw
    /// std::logic_error, and nodes() and balls() are empty.
    explicit TriangleBvh(const TriangleSoup& soup, BvhSplit split = BvhSplit::SurfaceArea,
                         BvhQueries queries = BvhQueries::All);

    /// Calls visit(i, j) once for every pair of distinct triangles whose
    /// bounding boxes overlap (as floats rounded outward: a few pairs more
    /// that only touch within float rounding, never fewer).
    template <class Visit>
    void selfPairs(Visit&& visit) const {
        if (!pairNodes_.empty()) selfPairsUnder({0, 0}, visit);
    }

    /// A pair of nodes: the pairs of triangles, one under each (two
    /// different ones under the same node when both are the same), whose
    /// boxes overlap.
    using NodePair = std::pair<int, int>;
    /// Node pairs that share selfPairs' work between threads: every pair of
    /// triangles selfPairs visits lies under exactly one of them. About
    /// `count` of them (fewer where the tree is small; more, up to twice,
    /// where one split makes several), in a fixed order. O(count).
    std::vector<NodePair> selfPairTasks(std::size_t count) const;
    /// selfPairs' visits under one node pair, in a fixed order.
    template <class Visit>
    void selfPairsUnder(NodePair task, Visit&& visit) const {
        selfPairsUnder(task, visit, [](int, int) { return false; });
    }
    /// The same, without descending into node pairs (a, b) for which
    /// skip(a, b) holds: their triangle pairs are not visited, the others
    /// in the same order. For searches that need not test whole subtrees
    /// (nodeGroups).
    template <class Visit, class Skip>
    void selfPairsUnder(NodePair task, Visit&& visit, Skip&& skip) const;

    /// Per node (as node pairs name them), the group that all its triangles
    /// have in `groupOf` (per triangle), or 0 where they differ or one of
    /// them is in group 0: a search that need not test pairs within one
    /// group (other than 0) skips node pairs with the same group.
    /// O(T + nodes).
    std::vector<std::uint32_t> nodeGroups(const std::vector<std::uint32_t>& groupOf) const;

    struct Nearest {
        std::size_t triangle = 0;
        double distance = INFINITY;
        Vec3 point;                   // on the triangle
        double distance2 = INFINITY;  // distance squared, as compared in the search
    };
    /// The triangle nearest to p and the distance; O(log T) typically.
    /// A `hint` (a triangle likely near p, e.g. the answer for a point close
    /// by) prunes the search from the start; the answer is the same.
    Nearest nearest(Vec3 p, std::size_t hint = SIZE_MAX) const;
    /// The same, among triangles nearer than sqrt(maxDistance2) (strictly):
    /// a search bounded by a distance already found elsewhere. When none is
    /// that near, triangle is SIZE_MAX and distance infinite.
    Nearest nearestWithin(Vec3 p, double maxDistance2, std::size_t hint = SIZE_MAX) const;

    /// The hierarchy as flat arrays, for device kernels that walk it:
    /// node 0 is the root; a leaf's triangles are order()[first, first+count).
    struct Node {
        Box3 box;
        int left = -1, right = -1;         // children, or -1 for a leaf
        std::size_t first = 0, count = 0;  // leaf range in order_
    };
    const std::vector<Node>& nodes() const { return nodes_; }
    /// Per triangle, a ball around it: its centroid and (slightly more than)
    /// its farthest corner's distance. |p - centre| - radius is a lower bound
    /// of p's distance to the triangle, tighter than a leaf's box for points
    /// far away, so most of a visited leaf's triangles are never measured.
    struct Ball {
        Vec3 centre;
        double radius = 0;
        /// The ball around triangle abc.
        static Ball around(Vec3 a, Vec3 b, Vec3 c);
        /// A lower bound of p's distance to the triangle (≤ 0 inside).
        double reach(Vec3 p) const { return length(p - centre) - radius; }
    };
    const std::vector<Ball>& balls() const { return balls_; }
    const std::vector<std::size_t>& order() const { return order_; }
    const TriangleSoup& soup() const { return soup_; }

  private:
    struct BuildItem {
        Box3 box;
        std::size_t triangle;
    };
    int build(std::vector<BuildItem>& items, std::vector<BuildItem>& scratch, std::size_t first,
              std::size_t last, int depth, BvhSplit how);
    /// Orders items[first, last), whose boxes span `box`, into two non-empty
    /// parts and returns where the second starts: by the surface area
    /// heuristic, or by count (at the median along box's longest axis) when
    /// !byArea or no plane separates.
    static std::size_t split(std::vector<BuildItem>& items, std::vector<BuildItem>& scratch,
                             std::size_t first, std::size_t last, const Box3& box, bool byArea);
    static std::size_t halve(std::vector<BuildItem>& items, std::size_t first, std::size_t last,
                             const Box3& box);
    void packForSearch();
    /// The pair search's copy (below), in two steps so the build items can
    /// go between them: the leaves' triangle boxes from `items` (in leaf
    /// order, as the build leaves them), then the nodes.
    void packLeafBoxes(const std::vector<BuildItem>& items);
    void packPairNodes();
    /// The node pairs that cover an inner node pair (a, b) (not two leaves),
    /// written to `out`; returns how many (2 or 3).
    int splitPair(NodePair pair, NodePair out[3]) const {
        const auto [a, b] = pair;
        const PairNode &na = pairNodes_[std::size_t(a)], &nb = pairNodes_[std::size_t(b)];
        if (a == b) {
            out[0] = {na.left, na.left};
            out[1] = {na.right, na.right};
            out[2] = {na.left, na.right};
            return 3;
        }
        if (na.left >= 0 && (nb.left < 0 || na.count >= nb.count)) {
            out[0] = {na.left, b};
            out[1] = {na.right, b};
        } else {
            out[0] = {a, nb.left};
            out[1] = {a, nb.right};
        }
        return 2;
    }
    bool boxesOverlap(NodePair pair) const {
        return pairNodes_[std::size_t(pair.first)].box.overlaps(
            pairNodes_[std::size_t(pair.second)].box);
    }

    const TriangleSoup& soup_;
    std::vector<Ball> balls_;
    std::vector<Node> nodes_;
    std::vector<std::size_t> order_;

    // The nearest search's own copy of the hierarchy, laid out for it (the
    // same boxes, corners and balls, so the same answers): both children's
    // boxes in their parent, so a visit reads one node, not three; and each
    // leaf's triangles side by side with their corners, so a leaf is one run
    // of memory instead of a jump per triangle and corner. The search is
    // most of simplification's time, and it is bound by memory.
    struct SearchNode {
        Box3 childBox[2];
        int child[2];  // >= 0: an inner node; < 0: leaf ~child
    };
    struct SearchLeaf {
        std::uint32_t first, count;  // into searchTriangles_
    };
    struct SearchTriangle {
        Vec3 corner[3];
        Ball ball;
        std::size_t triangle;
    };
    std::vector<SearchNode> searchNodes_;
    std::vector<SearchLeaf> searchLeaves_;
    std::vector<SearchTriangle> searchTriangles_;
    int searchRoot_ = 0;  // as SearchNode::child

    // The pair search's copy: the same hierarchy with float boxes rounded
    // outward (never smaller, so never a pair fewer) and leaves' triangle
    // boxes side by side in leaf order: half the memory of nodes_ and a
    // double box per triangle.
    struct FloatBox {
        float lo[3], hi[3];
        bool overlaps(const FloatBox& o) const {
            return lo[0] <= o.hi[0] && o.lo[0] <= hi[0] && lo[1] <= o.hi[1] && o.lo[1] <= hi[1] &&
                   lo[2] <= o.hi[2] && o.lo[2] <= hi[2];
        }
        static FloatBox around(const Box3& box);
    };
    struct PairNode {
        FloatBox box;
        int left, right;             // children, or -1 for a leaf
        std::uint32_t first, count;  // leaf range in order_ and pairBoxes_
    };
    std::vector<PairNode> pairNodes_;  // as nodes_
    std::vector<FloatBox> pairBoxes_;  // pairBoxes_[k]: triangle order_[k]
};

template <class Visit, class Skip>
void TriangleBvh::selfPairsUnder(NodePair task, Visit&& visit, Skip&& skip) const {
    // Only pairs whose boxes overlap are pushed: most children pairs of a
    // surface's nodes miss each other.
    if (!boxesOverlap(task)) return;
    std::vector<NodePair> stack{task};
    while (!stack.empty()) {
        const auto [a, b] = stack.back();
        stack.pop_back();
        if (skip(a, b)) continue;
        const PairNode &na = pairNodes_[std::size_t(a)], &nb = pairNodes_[std::size_t(b)];
        if (na.left < 0 && nb.left < 0) {
            for (std::uint32_t p = 0; p < na.count; ++p)
                for (std::uint32_t q = (a == b ? p + 1 : 0); q < nb.count; ++q) {
                    const std::size_t i = na.first + p, j = nb.first + q;
                    if (pairBoxes_[i].overlaps(pairBoxes_[j])) visit(order_[i], order_[j]);
                }
        } else {
            NodePair children[3];
            const int n = splitPair({a, b}, children);
            for (int k = 0; k < n; ++k)
                if (boxesOverlap(children[k])) stack.push_back(children[k]);
        }
    }
}

}  // namespace dfrecon
