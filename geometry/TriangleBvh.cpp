#include "geometry/TriangleBvh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <stdexcept>

namespace dfrecon {

TriangleBvh::TriangleBvh(const TriangleSoup& soup, BvhSplit how, BvhQueries queries)
    : soup_(soup), order_(soup.triangles.size()) {
    const bool nearest = queries == BvhQueries::All;
    // Built over the boxes, reordered as they are split, so that every pass
    // runs through memory in order. Only area splits need a second buffer.
    std::vector<BuildItem> items(soup.triangles.size());
    for (std::size_t t = 0; t < items.size(); ++t) {
        items[t].triangle = t;
        for (std::uint32_t v : soup.triangles[t]) items[t].box.add(soup.points[v]);
    }
    if (nearest) {
        balls_.resize(items.size());
        for (std::size_t t = 0; t < items.size(); ++t) {
            const auto& tri = soup.triangles[t];
            balls_[t] = Ball::around(soup.points[tri[0]], soup.points[tri[1]], soup.points[tri[2]]);
        }
    }
    std::vector<BuildItem> scratch;
    if (how == BvhSplit::SurfaceArea) scratch.reserve(items.size());
    // Room for the most nodes a tree over these triangles can have: growing
    // by doubling held the old and the new array at once (three times the
    // nodes, the peak of a large check), while pages reserved and never
    // written take no memory.
    nodes_.reserve(std::max<std::size_t>(1, 2 * items.size()));
    if (!items.empty()) build(items, scratch, 0, items.size(), 0, how);
    for (std::size_t k = 0; k < items.size(); ++k) order_[k] = items[k].triangle;
    if (nearest) packForSearch();
    // The items are the largest buffer (a double box per triangle): freed as
    // soon as the leaves' float boxes are taken from them, before the float
    // nodes are made, which cut the peak of a 2.8 M-triangle check by a box
    // per triangle.
    packLeafBoxes(items);
    decltype(items)().swap(items);
    packPairNodes();
    // The pair search reads its own copy only.
    if (!nearest) decltype(nodes_)().swap(nodes_);
}

TriangleBvh::FloatBox TriangleBvh::FloatBox::around(const Box3& box) {
    FloatBox f;
    for (int a = 0; a < 3; ++a) {
        f.lo[a] = float(box.lo[a]);
        if (double(f.lo[a]) > box.lo[a]) f.lo[a] = std::nextafter(f.lo[a], -INFINITY);
        f.hi[a] = float(box.hi[a]);
        if (double(f.hi[a]) < box.hi[a]) f.hi[a] = std::nextafter(f.hi[a], INFINITY);
    }
    return f;
}

void TriangleBvh::packLeafBoxes(const std::vector<BuildItem>& items) {
    pairBoxes_.resize(items.size());
    for (std::size_t k = 0; k < items.size(); ++k) pairBoxes_[k] = FloatBox::around(items[k].box);
}

void TriangleBvh::packPairNodes() {
    pairNodes_.resize(nodes_.size());
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
        const Node& node = nodes_[n];
        pairNodes_[n] = {FloatBox::around(node.box), node.left, node.right,
                         std::uint32_t(node.first), std::uint32_t(node.count)};
    }
}

std::vector<std::uint32_t> TriangleBvh::nodeGroups(
    const std::vector<std::uint32_t>& groupOf) const {
    std::vector<std::uint32_t> groups(pairNodes_.size(), 0);
    // Children come after their parent (the build numbers nodes depth
    // first), so a backward pass sees both children before the parent.
    for (std::size_t n = pairNodes_.size(); n-- > 0;) {
        const PairNode& node = pairNodes_[n];
        if (node.left >= 0) {
            const std::uint32_t left = groups[std::size_t(node.left)];
            groups[n] = left == groups[std::size_t(node.right)] ? left : 0;
            continue;
        }
        std::uint32_t group = node.count > 0 ? groupOf[order_[node.first]] : 0;
        for (std::uint32_t k = 1; k < node.count && group != 0; ++k)
            if (groupOf[order_[node.first + k]] != group) group = 0;
        groups[n] = group;
    }
    return groups;
}

std::vector<TriangleBvh::NodePair> TriangleBvh::selfPairTasks(std::size_t count) const {
    std::vector<NodePair> tasks;
    if (pairNodes_.empty()) return tasks;
    // Breadth first: split the first task in line until there are enough or
    // only pairs of leaves are left; pairs whose boxes miss are dropped.
    std::vector<NodePair> queue{{0, 0}}, done;
    std::size_t head = 0;
    while (head < queue.size() && queue.size() - head + done.size() < count) {
        const NodePair pair = queue[head++];
        const PairNode &na = pairNodes_[std::size_t(pair.first)],
                       &nb = pairNodes_[std::size_t(pair.second)];
        if (!na.box.overlaps(nb.box)) continue;
        if (na.left < 0 && nb.left < 0) {
            done.push_back(pair);
        } else {
            NodePair children[3];
            const int n = splitPair(pair, children);
            queue.insert(queue.end(), children, children + n);
        }
    }
    tasks.assign(queue.begin() + std::ptrdiff_t(head), queue.end());
    tasks.insert(tasks.end(), done.begin(), done.end());
    return tasks;
}

TriangleBvh::Ball TriangleBvh::Ball::around(Vec3 a, Vec3 b, Vec3 c) {
    Ball ball{(1.0 / 3.0) * (a + b + c), 0};
    for (const Vec3& q : {a, b, c}) ball.radius = std::max(ball.radius, length(q - ball.centre));
    // Rounding must never make the bound exceed the true distance.
    ball.radius = ball.radius * (1 + 1e-12) + 1e-300;
    return ball;
}

void TriangleBvh::packForSearch() {
    if (nodes_.empty()) return;
    // Node index -> its reference in the packed arrays.
    std::vector<int> ref(nodes_.size());
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
        const Node& node = nodes_[n];
        if (node.left >= 0) {
            ref[n] = int(searchNodes_.size());
            searchNodes_.emplace_back();
            continue;
        }
        ref[n] = ~int(searchLeaves_.size());
        searchLeaves_.push_back(
            {std::uint32_t(searchTriangles_.size()), std::uint32_t(node.count)});
        for (std::size_t k = 0; k < node.count; ++k) {
            const std::size_t t = order_[node.first + k];
            const auto& tri = soup_.triangles[t];
            searchTriangles_.push_back(
                {{soup_.points[tri[0]], soup_.points[tri[1]], soup_.points[tri[2]]}, balls_[t], t});
        }
    }
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
        const Node& node = nodes_[n];
        if (node.left < 0) continue;
        SearchNode& packed = searchNodes_[std::size_t(ref[n])];
        const std::size_t children[2] = {std::size_t(node.left), std::size_t(node.right)};
        for (int c = 0; c < 2; ++c) {
            packed.childBox[c] = nodes_[children[c]].box;
            packed.child[c] = ref[children[c]];
        }
    }
    searchRoot_ = ref[0];
}

namespace {

// Area splits can peel off a few triangles at a time; below this depth the
// tree halves by count, so it stays within the searches' fixed stacks (64
// in the kernels: 24 + log2(T / 4) levels at most).
constexpr int kAreaSplitDepth = 24;

double halfArea(const Box3& b) {
    const Vec3 e = b.hi - b.lo;
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

}  // namespace

std::size_t TriangleBvh::split(std::vector<BuildItem>& items, std::vector<BuildItem>& scratch,
                               std::size_t first, std::size_t last, const Box3& box, bool byArea) {
    // Binned surface area heuristic over the box centres: the split that
    // minimises the children's area times their triangle counts, i.e. the
    // expected cost of a search that reaches this node. Nearest searches
    // from points inside a closed surface (most of simplification's) sit
    // in every box around them; smaller boxes are fewer visits.
    constexpr int kBins = 16;
    if (!byArea) return halve(items, first, last, box);
    auto centre = [](const BuildItem& item, int axis) {
        return 0.5 * (item.box.lo[axis] + item.box.hi[axis]);
    };
    Box3 centres;
    for (std::size_t k = first; k < last; ++k)
        centres.add(0.5 * (items[k].box.lo + items[k].box.hi));
    // The bin of an item's box centre along `axis`; written so that any
    // value, NaN included, lands in a bin.
    double scale[3];
    for (int axis = 0; axis < 3; ++axis)
        scale[axis] = kBins / (centres.hi[axis] - centres.lo[axis]);
    auto binOf = [&](const BuildItem& item, int axis) {
        const double x = (centre(item, axis) - centres.lo[axis]) * scale[axis];
        return x >= kBins - 1 ? kBins - 1 : (x > 0 ? int(x) : 0);
    };
    // One pass over the items (contiguous) for the three axes.
    Box3 bins[3][kBins];
    std::size_t counts[3][kBins] = {};
    for (std::size_t k = first; k < last; ++k)
        for (int axis = 0; axis < 3; ++axis) {
            const int b = binOf(items[k], axis);
            bins[axis][b].add(items[k].box);
            ++counts[axis][b];
        }
    double bestCost = INFINITY;
    int bestAxis = -1, bestBin = 0;  // the second part: bins bestBin and above
    for (int axis = 0; axis < 3; ++axis) {
        if (!(centres.hi[axis] > centres.lo[axis])) continue;
        // Sweep from the right, then from the left.
        double rightArea[kBins];
        std::size_t rightCount[kBins];
        Box3 sweep;
        std::size_t n = 0;
        for (int b = kBins - 1; b > 0; --b) {
            if (counts[axis][b]) sweep.add(bins[axis][b]);
            n += counts[axis][b];
            rightArea[b] = n ? halfArea(sweep) : 0;
            rightCount[b] = n;
        }
        sweep = Box3{};
        n = 0;
        for (int b = 0; b + 1 < kBins; ++b) {
            if (counts[axis][b]) sweep.add(bins[axis][b]);
            n += counts[axis][b];
            if (n == 0 || rightCount[b + 1] == 0) continue;
            const double cost =
                halfArea(sweep) * double(n) + rightArea[b + 1] * double(rightCount[b + 1]);
            if (cost < bestCost) {
                bestCost = cost;
                bestAxis = axis;
                bestBin = b + 1;
            }
        }
    }
    if (bestAxis >= 0) {
        // A stable partition through one reused buffer (std::stable_partition
        // allocates one per call, and the page faults cost more than the
        // partition).
        std::size_t mid = first;
        scratch.clear();
        for (std::size_t k = first; k < last; ++k) {
            if (binOf(items[k], bestAxis) < bestBin)
                items[mid++] = items[k];
            else
                scratch.push_back(items[k]);
        }
        std::copy(scratch.begin(), scratch.end(), items.begin() + std::ptrdiff_t(mid));
        if (mid > first && mid < last) return mid;
    }
    return halve(items, first, last, box);  // all centres together
}

std::size_t TriangleBvh::halve(std::vector<BuildItem>& items, std::size_t first, std::size_t last,
                               const Box3& box) {
    const Vec3 extent = box.hi - box.lo;
    const int axis =
        extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const std::size_t mid = (first + last) / 2;
    std::nth_element(items.begin() + std::ptrdiff_t(first), items.begin() + std::ptrdiff_t(mid),
                     items.begin() + std::ptrdiff_t(last),
                     [&](const BuildItem& a, const BuildItem& b) {
                         return a.box.lo[axis] + a.box.hi[axis] < b.box.lo[axis] + b.box.hi[axis];
                     });
    return mid;
}

int TriangleBvh::build(std::vector<BuildItem>& items, std::vector<BuildItem>& scratch,
                       std::size_t first, std::size_t last, int depth, BvhSplit how) {
    const int index = int(nodes_.size());
    nodes_.emplace_back();
    Box3 box;
    for (std::size_t k = first; k < last; ++k) box.add(items[k].box);
    nodes_[std::size_t(index)].box = box;
    if (last - first <= 4) {
        nodes_[std::size_t(index)].first = first;
        nodes_[std::size_t(index)].count = last - first;
        return index;
    }
    const bool byArea = how == BvhSplit::SurfaceArea && depth < kAreaSplitDepth;
    const std::size_t mid = split(items, scratch, first, last, box, byArea);
    const int left = build(items, scratch, first, mid, depth + 1, how);
    const int right = build(items, scratch, mid, last, depth + 1, how);
    nodes_[std::size_t(index)].left = left;
    nodes_[std::size_t(index)].right = right;
    nodes_[std::size_t(index)].count = last - first;
    return index;
}

TriangleBvh::Nearest TriangleBvh::nearest(Vec3 p, std::size_t hint) const {
    Nearest best = nearestWithin(p, INFINITY, hint);
    if (best.triangle == SIZE_MAX) best.triangle = 0;  // an empty soup
    return best;
}

TriangleBvh::Nearest TriangleBvh::nearestWithin(Vec3 p, double maxDistance2,
                                                std::size_t hint) const {
    if (!soup_.triangles.empty() && balls_.empty())
        throw std::logic_error("TriangleBvh: built for pairs only, not for nearest searches");
    Nearest best{SIZE_MAX, INFINITY, {}};
    if (nodes_.empty()) return best;
    double best2 = maxDistance2;
    if (hint < soup_.triangles.size()) {
        const auto& tri = soup_.triangles[hint];
        const Vec3 q = closestPointOnTriangle(p, soup_.points[tri[0]], soup_.points[tri[1]],
                                              soup_.points[tri[2]]);
        if (dot(p - q, p - q) < best2) {
            best2 = dot(p - q, p - q);
            best = {hint, 0, q};
        }
    }
    // The depth is at most 24 + log2(T/4) (build), and each pop pushes at
    // most two children, so a fixed stack suffices (no allocation per query).
    // Each entry keeps its box's distance, computed once when pushed.
    std::array<std::pair<int, double>, 128> stack;
    std::size_t size = 0;
    stack[size++] = {searchRoot_, nodes_[0].box.distance2(p)};
    while (size > 0) {
        const auto [ref, boxDistance2] = stack[--size];
        if (boxDistance2 >= best2) continue;
        if (ref < 0) {
            const SearchLeaf leaf = searchLeaves_[std::size_t(~ref)];
            for (std::uint32_t k = leaf.first; k < leaf.first + leaf.count; ++k) {
                const SearchTriangle& candidate = searchTriangles_[k];
                const double reach = candidate.ball.reach(p);
                if (reach > 0 && reach * reach >= best2) continue;
                const Vec3 q = closestPointOnTriangle(p, candidate.corner[0], candidate.corner[1],
                                                      candidate.corner[2]);
                const double d2 = dot(p - q, p - q);
                if (d2 < best2) {
                    best2 = d2;
                    best = {candidate.triangle, 0, q};
                }
            }
            continue;
        }
        // Nearer child last, so it is searched first.
        const SearchNode& node = searchNodes_[std::size_t(ref)];
        const double left = node.childBox[0].distance2(p), right = node.childBox[1].distance2(p);
        const bool leftNearer = left < right;
        stack[size++] =
            leftNearer ? std::pair{node.child[1], right} : std::pair{node.child[0], left};
        stack[size++] =
            leftNearer ? std::pair{node.child[0], left} : std::pair{node.child[1], right};
    }
    if (best.triangle != SIZE_MAX) {
        best.distance = std::sqrt(best2);
        best.distance2 = best2;
    }
    return best;
}

}  // namespace dfrecon
