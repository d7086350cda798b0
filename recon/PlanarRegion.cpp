#include "recon/PlanarRegion.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <map>
#include <stdexcept>

namespace dfrecon {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
// Exact predicates with intersection points constructed in doubles: edges of
// different contours may cross (an intermediate contour against an original
// one), and each crossing becomes a vertex of both.
using Cdt = CGAL::Constrained_triangulation_plus_2<
    CGAL::Constrained_Delaunay_triangulation_2<Kernel, CGAL::Default, CGAL::Exact_predicates_tag>>;

int weightedWinding(Point2 p, const std::vector<WeightedContour>& contours) {
    int sum = 0;
    for (const WeightedContour& c : contours) sum += c.weight * windingNumber(p, *c.polygon);
    return sum;
}

}  // namespace

PlanarRegion triangulateRegion(const std::vector<WeightedContour>& contours,
                               const std::vector<Point2>& steinerPoints) {
    Cdt cdt;
    std::vector<std::vector<Cdt::Vertex_handle>> corners(contours.size());
    for (std::size_t c = 0; c < contours.size(); ++c)
        for (Point2 p : *contours[c].polygon) corners[c].push_back(cdt.insert({p.x, p.y}));
    std::vector<std::vector<Cdt::Constraint_id>> constraints(contours.size());
    for (std::size_t c = 0; c < contours.size(); ++c) {
        const std::size_t n = corners[c].size();
        for (std::size_t k = 0; k < n; ++k)
            constraints[c].push_back(cdt.insert_constraint(corners[c][k], corners[c][(k + 1) % n]));
    }
    for (Point2 p : steinerPoints) cdt.insert({p.x, p.y});

    PlanarRegion region;
    std::map<Cdt::Vertex_handle, std::uint32_t> index;
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
            for (auto it = cdt.vertices_in_constraint_begin(constraints[c][k]);
                 it != cdt.vertices_in_constraint_end(constraints[c][k]); ++it)
                chain.push_back(indexOf(*it));
            if (chain.empty()) throw std::logic_error("triangulateRegion: lost a constraint");
            if (chain.front() != indexOf(corners[c][k])) chain.assign(chain.rbegin(), chain.rend());
            region.edgeChains[c].push_back(std::move(chain));
        }
    }
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
        const auto& a = f->vertex(0)->point();
        const auto& b = f->vertex(1)->point();
        const auto& d = f->vertex(2)->point();
        const Point2 centroid{(a.x() + b.x() + d.x()) / 3, (a.y() + b.y() + d.y()) / 3};
        const int w = weightedWinding(centroid, contours);
        if (w == 0) continue;
        region.triangles.push_back(
            {indexOf(f->vertex(0)), indexOf(f->vertex(1)), indexOf(f->vertex(2))});
        region.sign.push_back(w > 0 ? 1 : -1);
    }
    return region;
}

}  // namespace dfrecon
