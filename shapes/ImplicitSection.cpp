#include "shapes/ImplicitSection.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace dfrecon {

namespace {

// Marching squares on the cells of a quadtree that can hold the zero set.
// Nodes are (i, j) on a grid of n + 1 by n + 1; edges are keyed by their
// lower-left node and direction (0: towards +x, 1: towards +y).
class SectionTracer {
  public:
    SectionTracer(const std::function<double(Vec3)>& distance, Box2 region, double z, double cell)
        : f_(distance), z_(z), h_(cell) {
        // Two cells of margin so no crossing lies on the grid's border, and an
        // odd offset so nodes do not sit on the shapes' symmetry lines.
        x0_ = region.min.x - 2.37 * h_;
        y0_ = region.min.y - 2.41 * h_;
        const double size =
            std::max(region.max.x - region.min.x, region.max.y - region.min.y) + 5 * h_;
        n_ = 1;
        while (double(n_) * h_ < size) n_ *= 2;
    }

    std::vector<Polygon> trace(int points) {
        visit(0, 0, n_);
        buildSegments();
        std::vector<Polygon> polygons;
        for (const std::vector<std::uint64_t>& loop : loops()) {
            Polygon polygon = resample(loop, points);
            if (polygon.size() >= 3) polygons.push_back(std::move(polygon));
        }
        return polygons;
    }

  private:
    double eval(double x, double y) const { return f_(Vec3{x, y, z_}); }
    Point2 nodePoint(std::int64_t i, std::int64_t j) const { return {x0_ + i * h_, y0_ + j * h_}; }
    std::uint64_t nodeKey(std::int64_t i, std::int64_t j) const {
        return std::uint64_t(i) * std::uint64_t(n_ + 1) + std::uint64_t(j);
    }
    double node(std::int64_t i, std::int64_t j) {
        const auto [it, inserted] = nodes_.try_emplace(nodeKey(i, j), 0.0);
        if (inserted) {
            const Point2 p = nodePoint(i, j);
            it->second = eval(p.x, p.y);
        }
        return it->second;
    }
    // Inside is strictly negative, so a zero node counts as outside and a
    // crossing towards it ends exactly at it.
    static bool inside(double value) { return value < 0; }

    void visit(std::int64_t i, std::int64_t j, std::int64_t size) {
        const double half = 0.5 * double(size) * h_;
        const double centre = eval(x0_ + i * h_ + half, y0_ + j * h_ + half);
        // 1-Lipschitz: a zero within the cell is at most the half-diagonal away.
        if (std::abs(centre) > half * std::sqrt(2.0) * (1 + 1e-9)) return;
        if (size == 1) {
            cells_.push_back({i, j});
            return;
        }
        const std::int64_t s = size / 2;
        visit(i, j, s);
        visit(i + s, j, s);
        visit(i, j + s, s);
        visit(i + s, j + s, s);
    }

    std::uint64_t edgeKey(std::int64_t i, std::int64_t j, int direction) const {
        return 2 * nodeKey(i, j) + std::uint64_t(direction);
    }
    void edgeNodes(std::uint64_t key, std::int64_t& ia, std::int64_t& ja, std::int64_t& ib,
                   std::int64_t& jb) const {
        const std::uint64_t nodeIndex = key / 2;
        ia = std::int64_t(nodeIndex / std::uint64_t(n_ + 1));
        ja = std::int64_t(nodeIndex % std::uint64_t(n_ + 1));
        ib = ia + (key % 2 == 0 ? 1 : 0);
        jb = ja + (key % 2 == 1 ? 1 : 0);
    }

    void addSegment(std::uint64_t a, std::uint64_t b) {
        const int index = int(segments_.size());
        segments_.push_back({a, b});
        for (std::uint64_t e : {a, b}) {
            auto& slots = edgeSegments_.try_emplace(e, std::array<int, 2>{-1, -1}).first->second;
            (slots[0] < 0 ? slots[0] : slots[1]) = index;
        }
    }

    void buildSegments() {
        for (const auto& [i, j] : cells_) {
            const double v[4] = {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)};
            int mask = 0;
            for (int k = 0; k < 4; ++k)
                if (inside(v[k])) mask |= 1 << k;
            if (mask == 0 || mask == 15) continue;
            // Edges: 0 bottom (c0 c1), 1 right (c1 c2), 2 top (c3 c2), 3 left (c0 c3).
            const std::uint64_t e[4] = {edgeKey(i, j, 0), edgeKey(i + 1, j, 1),
                                        edgeKey(i, j + 1, 0), edgeKey(i, j, 1)};
            if (mask == 5 || mask == 10) {
                // Saddle: the centre decides which diagonal the inside joins.
                const bool centreInside = inside(eval(x0_ + (i + 0.5) * h_, y0_ + (j + 0.5) * h_));
                const bool cornersJoined = (mask == 5) == centreInside;  // c0, c2 joined
                if (cornersJoined) {
                    addSegment(e[0], e[1]);  // cuts off c1
                    addSegment(e[2], e[3]);  // cuts off c3
                } else {
                    addSegment(e[3], e[0]);  // cuts off c0
                    addSegment(e[1], e[2]);  // cuts off c2
                }
                continue;
            }
            std::uint64_t crossing[2];
            int count = 0;
            static constexpr int kEnds[4][2] = {{0, 1}, {1, 2}, {3, 2}, {0, 3}};
            for (int k = 0; k < 4; ++k)
                if (inside(v[kEnds[k][0]]) != inside(v[kEnds[k][1]])) crossing[count++] = e[k];
            if (count == 2) addSegment(crossing[0], crossing[1]);
        }
    }

    std::vector<std::vector<std::uint64_t>> loops() const {
        std::vector<std::vector<std::uint64_t>> result;
        std::vector<bool> used(segments_.size(), false);
        for (std::size_t s0 = 0; s0 < segments_.size(); ++s0) {
            if (used[s0]) continue;
            used[s0] = true;
            std::vector<std::uint64_t> loop{segments_[s0][0]};
            const std::uint64_t first = segments_[s0][0];
            std::uint64_t edge = segments_[s0][1];
            int previous = int(s0);
            bool closed = true;
            while (edge != first) {
                loop.push_back(edge);
                const std::array<int, 2>& slots = edgeSegments_.at(edge);
                const int next = slots[0] == previous ? slots[1] : slots[0];
                if (next < 0 || used[std::size_t(next)]) {
                    closed = false;  // cannot happen with the border margin
                    break;
                }
                used[std::size_t(next)] = true;
                const auto& seg = segments_[std::size_t(next)];
                edge = seg[0] == edge ? seg[1] : seg[0];
                previous = next;
            }
            if (closed) result.push_back(std::move(loop));
        }
        return result;
    }

    Point2 linearCrossing(std::uint64_t key) const {
        std::int64_t ia, ja, ib, jb;
        edgeNodes(key, ia, ja, ib, jb);
        const double fa = nodes_.at(nodeKey(ia, ja)), fb = nodes_.at(nodeKey(ib, jb));
        const double t = fa / (fa - fb);
        return nodePoint(ia, ja) + t * (nodePoint(ib, jb) - nodePoint(ia, ja));
    }

    // The root of the distance on a crossed edge, by the Illinois variant of
    // regula falsi (bracketing, so it cannot leave the edge).
    Point2 exactCrossing(std::uint64_t key) const {
        std::int64_t ia, ja, ib, jb;
        edgeNodes(key, ia, ja, ib, jb);
        Point2 a = nodePoint(ia, ja), b = nodePoint(ib, jb);
        double fa = nodes_.at(nodeKey(ia, ja)), fb = nodes_.at(nodeKey(ib, jb));
        if (!inside(fa)) {
            std::swap(a, b);
            std::swap(fa, fb);
        }
        if (fb == 0) return b;
        double lo = 0, hi = 1, flo = fa, fhi = fb;
        Point2 best = std::abs(fa) < std::abs(fb) ? a : b;
        double bestValue = std::min(std::abs(fa), std::abs(fb));
        int side = 0;
        for (int iteration = 0; iteration < 200 && hi - lo > 1e-17; ++iteration) {
            double t = (lo * fhi - hi * flo) / (fhi - flo);
            if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
            const Point2 p = a + t * (b - a);
            const double value = eval(p.x, p.y);
            if (std::abs(value) < bestValue) {
                bestValue = std::abs(value);
                best = p;
            }
            if (value == 0) break;
            if (inside(value)) {
                lo = t;
                flo = value;
                if (side == -1) fhi *= 0.5;
                side = -1;
            } else {
                hi = t;
                fhi = value;
                if (side == 1) flo *= 0.5;
                side = 1;
            }
        }
        return best;
    }

    // `points` crossings of the loop, evenly spaced by arc length, each then
    // moved to the exact root on its edge.
    Polygon resample(const std::vector<std::uint64_t>& loop, int points) const {
        const std::size_t m = loop.size();
        std::vector<Point2> positions(m);
        for (std::size_t k = 0; k < m; ++k) positions[k] = linearCrossing(loop[k]);
        std::vector<double> along(m + 1, 0.0);
        for (std::size_t k = 0; k < m; ++k)
            along[k + 1] = along[k] + length(positions[(k + 1) % m] - positions[k]);
        const std::size_t n = std::min<std::size_t>(std::size_t(std::max(points, 3)), m);
        Polygon polygon;
        std::size_t next = 0;
        for (std::size_t k = 0; k < n; ++k) {
            const double target = along[m] * double(k) / double(n);
            std::size_t pick = next;
            while (pick + 1 < m && along[pick + 1] <= target) ++pick;
            if (pick + 1 < m && along[pick + 1] - target < target - along[pick]) ++pick;
            pick = std::min(pick, m - (n - k));  // leave one crossing for each remaining vertex
            const Point2 p = exactCrossing(loop[pick]);
            if (polygon.empty() || p != polygon.back()) polygon.push_back(p);
            next = pick + 1;
        }
        while (polygon.size() > 1 && polygon.front() == polygon.back()) polygon.pop_back();
        return polygon;
    }

    const std::function<double(Vec3)>& f_;
    double z_, h_, x0_ = 0, y0_ = 0;
    std::int64_t n_ = 1;
    std::unordered_map<std::uint64_t, double> nodes_;
    std::vector<std::array<std::int64_t, 2>> cells_;
    std::vector<std::array<std::uint64_t, 2>> segments_;
    std::unordered_map<std::uint64_t, std::array<int, 2>> edgeSegments_;
};

}  // namespace

std::vector<Polygon> implicitSection(const std::function<double(Vec3)>& distance, Box2 region,
                                     double z, double cellMm, int points) {
    if (region.empty() || !(cellMm > 0)) return {};
    return SectionTracer(distance, region, z, cellMm).trace(points);
}

double sectionedVolume(const std::function<double(Vec3)>& distance, Box2 region, double zMin,
                       double zMax, double dzMm, double cellMm) {
    const int n = std::max(1, int(std::ceil((zMax - zMin) / dzMm)));
    const double dz = (zMax - zMin) / n;
    double volume = 0;
    for (int i = 0; i < n; ++i) {
        const std::vector<Polygon> section =
            implicitSection(distance, region, zMin + dz * (i + 0.5), cellMm, 1 << 30);
        for (std::size_t c = 0; c < section.size(); ++c) {
            // Contours do not cross, so one vertex tells what encloses it.
            int depth = 0;
            for (std::size_t other = 0; other < section.size(); ++other)
                if (other != c && windingNumber(section[c][0], section[other]) != 0) ++depth;
            volume += (depth % 2 == 0 ? 1 : -1) * std::abs(signedArea(section[c])) * dz;
        }
    }
    return volume;
}

}  // namespace dfrecon
