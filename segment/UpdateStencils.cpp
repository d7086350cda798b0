#include "segment/UpdateStencils.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace dfrecon {

namespace {

struct Vec2 {
    double x = 0, y = 0;
};
Vec2 operator-(Vec2 a, Vec2 b) {
    return {a.x - b.x, a.y - b.y};
}
double dot(Vec2 a, Vec2 b) {
    return a.x * b.x + a.y * b.y;
}
double cross(Vec2 a, Vec2 b) {
    return a.x * b.y - a.y * b.x;
}
double norm(Vec2 a) {
    return std::sqrt(dot(a, a));
}

/// The point at distances dp from p and dq from q, on the side of line pq
/// away from `away` (the unfolded apex of the triangle just left).
Vec2 unfoldAcross(Vec2 p, Vec2 q, double dp, double dq, Vec2 away) {
    const Vec2 e = q - p;
    const double l = norm(e);
    const Vec2 u{e.x / l, e.y / l};
    const Vec2 left{-u.y, u.x};
    const double along = (dp * dp - dq * dq + l * l) / (2 * l);
    const double across = std::sqrt(std::max(dp * dp - along * along, 0.0));
    const double side = cross(e, away - p) > 0 ? -1.0 : 1.0;
    return {p.x + along * u.x + side * across * left.x, p.y + along * u.y + side * across * left.y};
}

struct VirtualVertex {
    int vertex = 0;
    Vec2 position;  // in the frame C = (0, 0), A on the positive x axis
};

/// The walk of Kimmel & Sethian from triangle t, obtuse at corner `corner`
/// (C): across the edge opposite C, then across whichever edge of each
/// unfolded triangle the cone at C still passes through.
std::optional<VirtualVertex> findVirtualVertex(const MeshGraph& graph, int t, int corner, Vec2 pa,
                                               Vec2 pb, int maxSteps) {
    const auto& tri = graph.triangle(t);
    const int c = tri[std::size_t(corner)];
    int p = tri[std::size_t((corner + 1) % 3)], q = tri[std::size_t((corner + 2) % 3)];
    Vec2 pp = pa, pq = pb, apex{0, 0};
    int current = t;
    for (int step = 0; step < maxSteps; ++step) {
        const int cornerP = graph.cornerOf(current, p), cornerQ = graph.cornerOf(current, q);
        const int next = graph.neighbour(current, 3 - cornerP - cornerQ);
        if (next < 0) return std::nullopt;
        const auto& nt = graph.triangle(next);
        const int d = nt[0] != p && nt[0] != q ? nt[0] : nt[1] != p && nt[1] != q ? nt[1] : nt[2];
        if (d == c) return std::nullopt;
        const Vec2 pd = unfoldAcross(pp, pq, length(graph.point(d) - graph.point(p)),
                                     length(graph.point(d) - graph.point(q)), apex);
        const bool pastA = dot(pd, pa) <= 0, pastB = dot(pd, pb) <= 0;
        if (!pastA && !pastB) return VirtualVertex{d, pd};
        if (pastA && pastB) return std::nullopt;  // behind C: the strip folded back
        // pastA: D lies beyond the cone on B's side, so the cone leaves
        // through edge PD; otherwise through DQ.
        apex = pastA ? pq : pp;
        if (pastA) {
            q = d;
            pq = pd;
        } else {
            p = d;
            pp = pd;
        }
        current = next;
    }
    return std::nullopt;
}

UpdateStencil stencil(int a, int b, Vec2 pa, Vec2 pb) {
    const double la = norm(pa), lb = norm(pb);
    return {a, b, la, lb, std::clamp(dot(pa, pb) / (la * lb), -1.0, 1.0)};
}

}  // namespace

UpdateStencils::UpdateStencils(const MeshGraph& graph, const UnfoldOptions& options) {
    const int n = graph.vertexCount();
    meanEdgeLength_ = graph.meanEdgeLength();
    first_.assign(std::size_t(n) + 1, 0);
    stencils_.reserve(graph.triangles().size() * 3);
    for (int c = 0; c < n; ++c) {
        for (int t : graph.trianglesAround(c)) {
            const int corner = graph.cornerOf(t, c);
            const auto& tri = graph.triangle(t);
            const int a = tri[std::size_t((corner + 1) % 3)],
                      b = tri[std::size_t((corner + 2) % 3)];
            const Vec3 pc = graph.point(c);
            const Vec3 ea = graph.point(a) - pc, eb = graph.point(b) - pc;
            const double la = length(ea), lb = length(eb);
            if (la <= 0 || lb <= 0) continue;  // coincident points: no direction to update from
            const double cosC = std::clamp(dot(ea, eb) / (la * lb), -1.0, 1.0);
            const Vec2 pa{la, 0}, pb{lb * cosC, lb * std::sqrt(1 - cosC * cosC)};
            if (cosC < 0) {
                ++obtuseCorners_;
                if (options.unfoldObtuse) {
                    if (auto w =
                            findVirtualVertex(graph, t, corner, pa, pb, options.maxUnfoldSteps)) {
                        stencils_.push_back(stencil(a, w->vertex, pa, w->position));
                        stencils_.push_back(stencil(w->vertex, b, w->position, pb));
                        continue;
                    }
                    ++unfoldFailures_;
                    // No virtual vertex: update along the two edges only
                    // (cosAngle 1, an empty angle, has no face update). An
                    // obtuse face update would make the scheme order-
                    // dependent (FIM and fast marching would then disagree
                    // downstream of it); edges keep it causal.
                    stencils_.push_back({a, b, la, lb, 1.0});
                    continue;
                }
            }
            stencils_.push_back({a, b, la, lb, cosC});
        }
        first_[std::size_t(c) + 1] = int(stencils_.size());
    }

    // Uses and dependents: the same relation keyed by the two corners.
    useFirst_.assign(std::size_t(n) + 1, 0);
    for (const UpdateStencil& s : stencils_) {
        ++useFirst_[std::size_t(s.a) + 1];
        ++useFirst_[std::size_t(s.b) + 1];
    }
    for (int v = 0; v < n; ++v) useFirst_[std::size_t(v) + 1] += useFirst_[std::size_t(v)];
    uses_.resize(stencils_.size() * 2);
    std::vector<int> fill(useFirst_.begin(), useFirst_.end() - 1);
    for (int target = 0; target < n; ++target)
        for (int k = first_[std::size_t(target)]; k < first_[std::size_t(target) + 1]; ++k) {
            const UpdateStencil& s = stencils_[std::size_t(k)];
            uses_[std::size_t(fill[std::size_t(s.a)]++)] = {k, target};
            uses_[std::size_t(fill[std::size_t(s.b)]++)] = {k, target};
        }
    dependentFirst_.assign(std::size_t(n) + 1, 0);
    dependents_.reserve(uses_.size() / 2);
    std::vector<int> row;
    for (int v = 0; v < n; ++v) {
        row.clear();
        for (int k = useFirst_[std::size_t(v)]; k < useFirst_[std::size_t(v) + 1]; ++k)
            row.push_back(uses_[std::size_t(k)].target);
        std::sort(row.begin(), row.end());
        row.erase(std::unique(row.begin(), row.end()), row.end());
        dependents_.insert(dependents_.end(), row.begin(), row.end());
        dependentFirst_[std::size_t(v) + 1] = int(dependents_.size());
    }
}

}  // namespace dfrecon
