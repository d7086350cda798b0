#include "geometry/TriangleBvh.hpp"

#include <algorithm>
#include <array>
#include <numeric>

namespace dfrecon {

TriangleBvh::TriangleBvh(const TriangleSoup& soup)
    : soup_(soup),
      boxes_(soup.triangles.size()),
      balls_(soup.triangles.size()),
      order_(soup.triangles.size()) {
    for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
        const auto& tri = soup.triangles[t];
        for (std::uint32_t v : tri) boxes_[t].add(soup.points[v]);
        Ball& ball = balls_[t];
        ball.centre =
            (1.0 / 3.0) * (soup.points[tri[0]] + soup.points[tri[1]] + soup.points[tri[2]]);
        for (std::uint32_t v : tri)
            ball.radius = std::max(ball.radius, length(soup.points[v] - ball.centre));
        // Rounding must never make the bound exceed the true distance.
        ball.radius = ball.radius * (1 + 1e-12) + 1e-300;
    }
    std::iota(order_.begin(), order_.end(), 0);
    if (!boxes_.empty()) build(0, boxes_.size());
}

int TriangleBvh::build(std::size_t first, std::size_t last) {
    const int index = int(nodes_.size());
    nodes_.emplace_back();
    Box3 box;
    for (std::size_t k = first; k < last; ++k) box.add(boxes_[order_[k]]);
    nodes_[std::size_t(index)].box = box;
    if (last - first <= 4) {
        nodes_[std::size_t(index)].first = first;
        nodes_[std::size_t(index)].count = last - first;
        return index;
    }
    const Vec3 extent = box.hi - box.lo;
    const int axis =
        extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const std::size_t mid = (first + last) / 2;
    std::nth_element(order_.begin() + std::ptrdiff_t(first), order_.begin() + std::ptrdiff_t(mid),
                     order_.begin() + std::ptrdiff_t(last), [&](std::size_t a, std::size_t b) {
                         return boxes_[a].lo[axis] + boxes_[a].hi[axis] <
                                boxes_[b].lo[axis] + boxes_[b].hi[axis];
                     });
    const int left = build(first, mid);
    const int right = build(mid, last);
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
    // Median splits keep the depth near log2(T/4), and each pop pushes at
    // most two children, so a fixed stack suffices (no allocation per query).
    // Each entry keeps its box's distance, computed once when pushed.
    std::array<std::pair<int, double>, 128> stack;
    std::size_t size = 0;
    stack[size++] = {0, nodes_[0].box.distance2(p)};
    while (size > 0) {
        const auto [index, boxDistance2] = stack[--size];
        if (boxDistance2 >= best2) continue;
        const Node& node = nodes_[std::size_t(index)];
        if (node.left < 0) {
            for (std::size_t k = 0; k < node.count; ++k) {
                const std::size_t t = order_[node.first + k];
                const double reach = length(p - balls_[t].centre) - balls_[t].radius;
                if (reach > 0 && reach * reach >= best2) continue;
                const auto& tri = soup_.triangles[t];
                const Vec3 q = closestPointOnTriangle(p, soup_.points[tri[0]], soup_.points[tri[1]],
                                                      soup_.points[tri[2]]);
                const double d2 = dot(p - q, p - q);
                if (d2 < best2) {
                    best2 = d2;
                    best = {t, 0, q};
                }
            }
            continue;
        }
        // Nearer child last, so it is searched first.
        const double left = nodes_[std::size_t(node.left)].box.distance2(p),
                     right = nodes_[std::size_t(node.right)].box.distance2(p);
        const bool leftNearer = left < right;
        stack[size++] = leftNearer ? std::pair{node.right, right} : std::pair{node.left, left};
        stack[size++] = leftNearer ? std::pair{node.left, left} : std::pair{node.right, right};
    }
    if (best.triangle != SIZE_MAX) {
        best.distance = std::sqrt(best2);
        best.distance2 = best2;
    }
    return best;
}

}  // namespace dfrecon
