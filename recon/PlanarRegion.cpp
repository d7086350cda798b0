#include "recon/PlanarRegion.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Handle_hash_function.h>

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <unordered_map>

namespace dfrecon {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
// Exact predicates with intersection points constructed in doubles: edges of
// different contours may cross (an intermediate contour against an original
// one), and each crossing becomes a vertex of both.
using Cdt = CGAL::Constrained_triangulation_plus_2<
    CGAL::Constrained_Delaunay_triangulation_2<Kernel, CGAL::Default, CGAL::Exact_predicates_tag>>;

}  // namespace

PlanarRegion triangulateRegion(const std::vector<WeightedContour>& contours,
                               const std::vector<Point2>& steinerPoints) {
    Cdt cdt;
    std::vector<std::vector<Cdt::Vertex_handle>> corners(contours.size());
    for (std::size_t c = 0; c < contours.size(); ++c)
        for (Point2 p : *contours[c].polygon) corners[c].push_back(cdt.insert({p.x, p.y}));
    // An edge whose ends are one vertex (two equal points in a row, as an
    // intermediate contour can have once rounded) is no constraint: CGAL
    // gives it a null id, whose vertices must not be asked for (a crash on
    // a generated lung, corpus VesselHoles seed 274).
    std::vector<std::vector<std::optional<Cdt::Constraint_id>>> constraints(contours.size());
    for (std::size_t c = 0; c < contours.size(); ++c) {
        const std::size_t n = corners[c].size();
        for (std::size_t k = 0; k < n; ++k) {
            const Cdt::Vertex_handle from = corners[c][k], to = corners[c][(k + 1) % n];
            constraints[c].push_back(from == to ? std::nullopt
                                                : std::optional(cdt.insert_constraint(from, to)));
        }
    }
    for (Point2 p : steinerPoints) cdt.insert({p.x, p.y});

    PlanarRegion region;
    // Hashed, not ordered: these lookups were a tenth of a large structure
    // set's reconstruction time.
    std::unordered_map<Cdt::Vertex_handle, std::uint32_t, CGAL::Handle_hash_function> index;
    auto indexOf = [&](Cdt::Vertex_handle v) {
        auto [it, fresh] = index.emplace(v, std::uint32_t(region.points.size()));
        if (fresh) region.points.push_back({v->point().x(), v->point().y()});
        return it->second;
    };
    region.edgeChains.resize(contours.size());
    for (std::size_t c = 0; c < contours.size(); ++c) {
        const std::size_t n = corners[c].size();
        for (std::size_t k = 0; k < n; ++k) {
            std::vector<std::uint32_t> chain;
            if (!constraints[c][k]) {  // a point: the edge's chain is its one vertex
                region.edgeChains[c].push_back({indexOf(corners[c][k])});
                continue;
            }
            for (auto it = cdt.vertices_in_constraint_begin(*constraints[c][k]);
                 it != cdt.vertices_in_constraint_end(*constraints[c][k]); ++it)
                chain.push_back(indexOf(*it));
            if (chain.empty()) throw std::logic_error("triangulateRegion: lost a constraint");
            if (chain.front() != indexOf(corners[c][k])) chain.assign(chain.rbegin(), chain.rend());
            region.edgeChains[c].push_back(std::move(chain));
        }
    }
    // Winding numbers by walking faces outward-in from the unbounded region
    // (winding 0): crossing a contour edge changes it by that contour's
    // weight, with the sign of the crossing's direction. Exact, unlike
    // winding numbers at centroids, which slivers along a contour make
    // unreliable.
    auto key = [](std::uint32_t from, std::uint32_t to) {
        return (std::uint64_t(from) << 32) | to;
    };
    std::unordered_map<std::uint64_t, int> crossing;  // directed edge → Σ weight
    for (std::size_t c = 0; c < contours.size(); ++c)
        for (const std::vector<std::uint32_t>& chain : region.edgeChains[c])
            for (std::size_t k = 0; k + 1 < chain.size(); ++k)
                crossing[key(chain[k], chain[k + 1])] += contours[c].weight;
    auto weightOf = [&](std::uint32_t from, std::uint32_t to) {
        const auto it = crossing.find(key(from, to));
        return it == crossing.end() ? 0 : it->second;
    };
    std::unordered_map<Cdt::Face_handle, int, CGAL::Handle_hash_function> winding;
    std::vector<Cdt::Face_handle> pending;
    for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f)
        if (cdt.is_infinite(f)) {
            winding[f] = 0;
            pending.push_back(f);
        }
    while (!pending.empty()) {
        const Cdt::Face_handle f = pending.back();
        pending.pop_back();
        for (int i = 0; i < 3; ++i) {
            const Cdt::Face_handle g = f->neighbor(i);
            if (winding.count(g)) continue;
            // f lies left of p→q (its counter-clockwise edge), g left of q→p.
            const Cdt::Vertex_handle p = f->vertex(Cdt::ccw(i)), q = f->vertex(Cdt::cw(i));
            if (cdt.is_infinite(p) || cdt.is_infinite(q)) continue;
            const std::uint32_t ip = indexOf(p), iq = indexOf(q);
            winding[g] = winding[f] + weightOf(iq, ip) - weightOf(ip, iq);
            pending.push_back(g);
        }
    }
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
        const int w = winding[f];
        if (w == 0) continue;
        region.triangles.push_back(
            {indexOf(f->vertex(0)), indexOf(f->vertex(1)), indexOf(f->vertex(2))});
        region.sign.push_back(w > 0 ? 1 : -1);
    }
    return region;
}

}  // namespace dfrecon
