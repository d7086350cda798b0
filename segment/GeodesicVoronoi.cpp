#include "segment/GeodesicVoronoi.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <set>
#include <unordered_map>

#include "segment/LocalUpdate.hpp"

namespace dfrecon {

namespace {

/// The time at which region `region`'s front reaches v if it may go one
/// vertex past its own region: the best update of v from stencils whose
/// corners belong to that region. kUnreached if no corner does.
double overlapTime(int v, int region, const FastMarching& marching, const GeodesicField& field) {
    const UpdateStencils& stencils = marching.stencils();
    double best = kUnreached;
    for (int k = stencils.first()[std::size_t(v)]; k < stencils.first()[std::size_t(v) + 1]; ++k) {
        const UpdateStencil& s = stencils.stencils()[std::size_t(k)];
        const bool inA = field.label[std::size_t(s.a)] == region;
        const bool inB = field.label[std::size_t(s.b)] == region;
        if (!inA && !inB) continue;
        const TriangleUpdate u = triangleUpdate(inA ? field.time[std::size_t(s.a)] : kUnreached,
                                                inB ? field.time[std::size_t(s.b)] : kUnreached,
                                                {s.lengthA, s.lengthB, s.cosAngle},
                                                marching.slowness()[std::size_t(v)], inA && inB);
        best = std::min(best, u.time);
    }
    return best;
}

int validLabel(const GeodesicField& field, int v, int regionCount) {
    const int l = field.label[std::size_t(v)];
    return l >= 0 && l < regionCount && std::isfinite(field.time[std::size_t(v)]) ? l : -1;
}

}  // namespace

double VoronoiRegions::compactness(int region) const {
    const double p = perimeter[std::size_t(region)];
    return p > 0 ? 4 * M_PI * area[std::size_t(region)] / (p * p) : 0.0;
}

VoronoiRegions geodesicVoronoi(const MeshGraph& graph, const FastMarching& marching,
                               const GeodesicField& field, int regionCount) {
    VoronoiRegions result;
    result.regionCount = regionCount;
    result.faceRegion.assign(graph.triangles().size(), -1);
    result.area.assign(std::size_t(regionCount), 0.0);
    result.perimeter.assign(std::size_t(regionCount), 0.0);
    std::vector<std::set<int>> neighbours{std::size_t(regionCount)};

    // Where the border crosses edge (v1, v2), as the fraction of the way
    // from v1. Overlap times are cached per (vertex, region).
    std::unordered_map<long long, double> overlaps;
    const auto overlap = [&](int v, int region) {
        const long long key = (long long)v * regionCount + region;
        auto [it, inserted] = overlaps.try_emplace(key, 0.0);
        if (inserted) it->second = overlapTime(v, region, marching, field);
        return it->second;
    };
    const auto crossing = [&](int v1, int r1, int v2, int r2) {
        const double own1 = field.time[std::size_t(v1)], own2 = field.time[std::size_t(v2)];
        const double lead1 = overlap(v1, r2) - own1;  // how far r2's front trails at v1
        const double lead2 = overlap(v2, r1) - own2;
        if (!std::isfinite(lead1) || !std::isfinite(lead2) || lead1 + lead2 <= 0) return 0.5;
        return std::clamp(lead1 / (lead1 + lead2), 0.0, 1.0);
    };
    const auto between = [](Vec3 p, Vec3 q, double s) { return p + s * (q - p); };
    const auto area3 = [](Vec3 a, Vec3 b, Vec3 c) { return 0.5 * length(cross(b - a, c - a)); };
    const auto border = [&](int r1, int r2, double len) {
        result.perimeter[std::size_t(r1)] += len;
        result.perimeter[std::size_t(r2)] += len;
        result.borderLength += len;
        neighbours[std::size_t(r1)].insert(r2);
        neighbours[std::size_t(r2)].insert(r1);
    };

    for (int t = 0; t < graph.triangleCount(); ++t) {
        const auto& tri = graph.triangle(t);
        std::array<int, 3> r{};
        std::array<Vec3, 3> p{};
        for (int k = 0; k < 3; ++k) {
            r[std::size_t(k)] = validLabel(field, tri[std::size_t(k)], regionCount);
            p[std::size_t(k)] = graph.point(tri[std::size_t(k)]);
        }
        const double whole = graph.triangleArea(t);
        std::array<double, 3> share{};  // area owned by corner k's region
        // Mesh-boundary edges belong to the regions of their ends, split at the crossing.
        for (int k = 0; k < 3; ++k) {
            if (graph.neighbour(t, k) >= 0) continue;
            const int i = (k + 1) % 3, j = (k + 2) % 3;
            const double len = length(p[std::size_t(j)] - p[std::size_t(i)]);
            const int ri = r[std::size_t(i)], rj = r[std::size_t(j)];
            if (ri == rj) {
                if (ri >= 0) result.perimeter[std::size_t(ri)] += len;
            } else if (ri >= 0 && rj >= 0) {
                const double s = crossing(tri[std::size_t(i)], ri, tri[std::size_t(j)], rj);
                result.perimeter[std::size_t(ri)] += s * len;
                result.perimeter[std::size_t(rj)] += (1 - s) * len;
            }
        }
        if (r[0] < 0 || r[1] < 0 || r[2] < 0) {
            // Not every corner reached: only the reached corners' thirds count.
            for (int k = 0; k < 3; ++k)
                if (r[std::size_t(k)] >= 0) share[std::size_t(k)] = whole / 3;
        } else if (r[0] == r[1] && r[1] == r[2]) {
            share[0] = whole;
        } else if (r[0] != r[1] && r[1] != r[2] && r[0] != r[2]) {
            std::array<Vec3, 3> m{};  // m[k] on edge (k, k+1)
            for (int k = 0; k < 3; ++k) {
                const int j = (k + 1) % 3;
                m[std::size_t(k)] = between(p[std::size_t(k)], p[std::size_t(j)],
                                            crossing(tri[std::size_t(k)], r[std::size_t(k)],
                                                     tri[std::size_t(j)], r[std::size_t(j)]));
            }
            const Vec3 centre = (1.0 / 3) * (m[0] + m[1] + m[2]);
            for (int k = 0; k < 3; ++k) {
                const int before = (k + 2) % 3;
                share[std::size_t(k)] = area3(p[std::size_t(k)], m[std::size_t(k)], centre) +
                                        area3(p[std::size_t(k)], centre, m[std::size_t(before)]);
                const int j = (k + 1) % 3;
                border(r[std::size_t(k)], r[std::size_t(j)], length(m[std::size_t(k)] - centre));
            }
        } else {
            // Two regions: corner `odd` alone against the other two.
            const int odd = r[1] == r[2] ? 0 : r[0] == r[2] ? 1 : 2;
            const int i = (odd + 1) % 3, j = (odd + 2) % 3;
            const int vo = tri[std::size_t(odd)], ro = r[std::size_t(odd)];
            const double si = crossing(vo, ro, tri[std::size_t(i)], r[std::size_t(i)]);
            const double sj = crossing(vo, ro, tri[std::size_t(j)], r[std::size_t(j)]);
            share[std::size_t(odd)] = si * sj * whole;
            share[std::size_t(i)] = whole - share[std::size_t(odd)];
            border(ro, r[std::size_t(i)],
                   length(between(p[std::size_t(odd)], p[std::size_t(i)], si) -
                          between(p[std::size_t(odd)], p[std::size_t(j)], sj)));
        }
        double largest = 0;
        for (int k = 0; k < 3; ++k) {
            const int region = r[std::size_t(k)];
            if (region < 0 || share[std::size_t(k)] <= 0) continue;
            result.area[std::size_t(region)] += share[std::size_t(k)];
            // Corners of one region share a piece: compare whole region shares.
            double regionShare = 0;
            for (int q = 0; q < 3; ++q)
                if (r[std::size_t(q)] == region) regionShare += share[std::size_t(q)];
            if (regionShare > largest) {
                largest = regionShare;
                result.faceRegion[std::size_t(t)] = region;
            }
        }
    }
    result.neighbours.resize(std::size_t(regionCount));
    for (int region = 0; region < regionCount; ++region)
        result.neighbours[std::size_t(region)].assign(neighbours[std::size_t(region)].begin(),
                                                      neighbours[std::size_t(region)].end());
    return result;
}

std::vector<RegionTopology> regionTopology(const MeshGraph& graph,
                                           const std::vector<int>& faceRegion, int regionCount) {
    std::vector<RegionTopology> topology{std::size_t(regionCount)};
    // Vertices: count each (vertex, region) once.
    for (int v = 0; v < graph.vertexCount(); ++v) {
        int seen[8];
        int seenCount = 0;
        std::vector<int> more;
        for (int t : graph.trianglesAround(v)) {
            const int region = faceRegion[std::size_t(t)];
            if (region < 0) continue;
            bool known = std::find(seen, seen + seenCount, region) != seen + seenCount ||
                         std::find(more.begin(), more.end(), region) != more.end();
            if (known) continue;
            if (seenCount < 8)
                seen[seenCount++] = region;
            else
                more.push_back(region);
            ++topology[std::size_t(region)].eulerCharacteristic;
        }
    }
    // Boundary loops: union-find over the (region, vertex) ends of boundary edges.
    std::unordered_map<long long, int> node;
    std::vector<int> parent;
    std::vector<int> nodeRegion;
    const auto nodeOf = [&](int region, int v) {
        auto [it, inserted] = node.try_emplace((long long)v * regionCount + region, 0);
        if (inserted) {
            it->second = int(parent.size());
            parent.push_back(it->second);
            nodeRegion.push_back(region);
        }
        return it->second;
    };
    const auto find = [&](int x) {
        while (parent[std::size_t(x)] != x) {
            parent[std::size_t(x)] = parent[std::size_t(parent[std::size_t(x)])];
            x = parent[std::size_t(x)];
        }
        return x;
    };
    for (int t = 0; t < graph.triangleCount(); ++t) {
        const int region = faceRegion[std::size_t(t)];
        if (region < 0) continue;
        RegionTopology& rt = topology[std::size_t(region)];
        ++rt.faces;
        ++rt.eulerCharacteristic;  // + F
        const auto& tri = graph.triangle(t);
        for (int k = 0; k < 3; ++k) {
            const int other = graph.neighbour(t, k);
            const bool inside = other >= 0 && faceRegion[std::size_t(other)] == region;
            // − E: an inside edge is seen from both faces, so half each time.
            if (inside) {
                if (other > t) --rt.eulerCharacteristic;
                continue;
            }
            --rt.eulerCharacteristic;
            const int a = nodeOf(region, tri[std::size_t((k + 1) % 3)]);
            const int b = nodeOf(region, tri[std::size_t((k + 2) % 3)]);
            parent[std::size_t(find(a))] = find(b);
        }
    }
    for (std::size_t x = 0; x < parent.size(); ++x)
        if (find(int(x)) == int(x)) ++topology[std::size_t(nodeRegion[x])].boundaryLoops;
    return topology;
}

}  // namespace dfrecon
