#include "compare/OverlapVolume.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "compare/IntersectionFlux.hpp"
#include "compare/OverlapRatios.hpp"
#include "geometry/MeshCheck.hpp"

namespace dfrecon {

namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

Mesh toCgal(const TriangleSoup& soup, const Vec3& shift = {}) {
    Mesh mesh;
    std::vector<Mesh::Vertex_index> vertices;
    vertices.reserve(soup.points.size());
    for (const Vec3& p : soup.points) {
        const Vec3 q = p + shift;
        vertices.push_back(mesh.add_vertex({q.x, q.y, q.z}));
    }
    for (const auto& t : soup.triangles)
        if (mesh.add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]) == Mesh::null_face())
            throw std::invalid_argument("a triangle could not be added (not manifold)");
    return mesh;
}

// An exact coordinate as a double, the same whatever was computed before:
// CGAL's to_double gives the midpoint of the current interval, which
// narrows when a predicate has needed the exact value, so the same point
// could round two ways. Input points (a single-point interval) are their
// double; constructed ones are rounded from their exact value.
double rounded(const Kernel::FT& x) {
    const CGAL::Interval_nt<false>& interval = x.approx();
    if (interval.inf() == interval.sup()) return interval.inf();
    return CGAL::to_double(x.exact());
}

// The enclosed volume from the exact points each rounded once to double:
// summing the tetrahedra in exact arithmetic (PMP::volume on Epeck) made
// every intersection point's rational coordinates exact and cost more than
// half of a 100 000-triangle overlap, for digits far below the rounding of
// the inputs' own points. The tetrahedra are summed in order of value,
// not in corefinement's face order, which follows memory addresses. The
// last digits can still differ between runs that allocated differently
// before (several pairs in one process): how corefinement triangulates a
// cut face follows addresses too.
double volumeOf(const Mesh& mesh) {
    std::vector<double> tetrahedra;
    tetrahedra.reserve(mesh.number_of_faces());
    for (const Mesh::Face_index face : mesh.faces()) {
        Vec3 corner[3];
        int k = 0;
        for (const Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(face), mesh)) {
            const Kernel::Point_3& p = mesh.point(v);
            if (k < 3) corner[k] = {rounded(p.x()), rounded(p.y()), rounded(p.z())};
            ++k;
        }
        tetrahedra.push_back(dot(corner[0], cross(corner[1], corner[2])) / 6);
    }
    std::sort(tetrahedra.begin(), tetrahedra.end());
    double volume = 0;
    for (const double t : tetrahedra) volume += t;
    return volume;
}

// How many points of `b` are exactly points of `a`. O(n log n).
std::size_t sharedPoints(const TriangleSoup& a, const TriangleSoup& b) {
    auto key = [](const Vec3& p) { return std::array<double, 3>{p.x, p.y, p.z}; };
    std::vector<std::array<double, 3>> points;
    points.reserve(a.points.size());
    for (const Vec3& p : a.points) points.push_back(key(p));
    std::sort(points.begin(), points.end());
    return std::size_t(std::count_if(b.points.begin(), b.points.end(), [&](const Vec3& p) {
        return std::binary_search(points.begin(), points.end(), key(p));
    }));
}

// Surfaces sharing this many points (neighbours cut from one label map
// share thousands of contour points) nearly always coincide along edges and
// faces too, where corefinement fails only after most of its work: they go
// straight to the shift. A few shared corners (boxes on one grid) do not.
bool likelyCoincideInPart(const TriangleSoup& a, const TriangleSoup& b) {
    const std::size_t fewer = std::min(a.points.size(), b.points.size());
    return sharedPoints(a, b) >= std::max<std::size_t>(16, fewer / 100);
}

}  // namespace

// Surfaces coinciding in part make a non-manifold intersection (false) or
// trip corefinement's constrained triangulation (an exception).
std::optional<double> intersectionVolume(const TriangleSoup& a, const TriangleSoup& b,
                                         const Vec3& shift) {
    // Corefinement refines both inputs along their intersection: copies.
    Mesh meshA = toCgal(a), meshB = toCgal(b, shift), meet;
    try {
        if (!CGAL::Polygon_mesh_processing::corefine_and_compute_intersection(meshA, meshB, meet))
            return std::nullopt;
    } catch (const CGAL::Failure_exception&) {
        return std::nullopt;
    }
    return volumeOf(meet);
}

Vec3 overlapShiftDirection() {
    const Vec3 generic{1.0, std::sqrt(2.0), std::sqrt(3.0) + 0.1};
    return (1.0 / length(generic)) * generic;
}

double Overlap::dice() const {
    return diceOf(volumeAMm3, volumeBMm3, intersectionMm3);
}

double Overlap::jaccard() const {
    return jaccardOf(volumeAMm3, volumeBMm3, intersectionMm3);
}

Overlap overlapOf(const TriangleSoup& a, const TriangleSoup& b) {
    return overlapOf(a, b, checkMesh(a), checkMesh(b));
}

std::optional<Overlap> overlapByFlux(const TriangleSoup& a, const TriangleSoup& b,
                                     const MeshCheckReport& checkA, const MeshCheckReport& checkB) {
    // The check measures what the overlap needs of each solid alone.
    for (const MeshCheckReport* check : {&checkA, &checkB})
        if (!check->validSolid())
            throw std::invalid_argument(std::string("surface ") + (check == &checkA ? "A" : "B") +
                                        " is not a valid closed solid (dfrecon check says where)");
    const double areaB = checkB.areaMm2;
    Overlap overlap;
    overlap.volumeAMm3 = checkA.volumeMm3;
    overlap.volumeBMm3 = checkB.volumeMm3;
    // The same surface twice: the intersection is the solid itself.
    if (a.points == b.points && a.triangles == b.triangles) {
        overlap.intersectionMm3 = overlap.volumeAMm3;
        return overlap;
    }
    // Surfaces that coincide in part (shared faces, edges or vertices) have
    // no general position: B is moved off A along a direction no face, edge
    // or axis of anatomy lies in, by a shift far below any tolerance yet far
    // above the coordinates' rounding (1e-13 mm at 500 mm), which the flux
    // needs no more than (its crossing points are where B's moved faces
    // meet A's transversally).
    const Vec3 direction = overlapShiftDirection();
    const bool shiftAtOnce = likelyCoincideInPart(a, b);
    for (const double shiftMm : {0.0, 1e-9, 1e-7, 1e-5}) {
        if (shiftMm == 0 && shiftAtOnce) continue;
        const IntersectionFlux flux = intersectionByFlux(a, b, shiftMm * direction);
        if (!flux.generalPosition) continue;
        overlap.intersectionMm3 = flux.volumeMm3;
        overlap.method = shiftMm > 0 ? "surface flux, B shifted" : "surface flux";
        overlap.shiftMm = shiftMm;
        overlap.intersectionBoundMm3 = flux.boundMm3 + areaB * shiftMm;
        return overlap;
    }
    return std::nullopt;
}

Overlap overlapOf(const TriangleSoup& a, const TriangleSoup& b, const MeshCheckReport& checkA,
                  const MeshCheckReport& checkB) {
    if (std::optional<Overlap> byFlux = overlapByFlux(a, b, checkA, checkB)) return *byFlux;
    Overlap overlap;
    overlap.volumeAMm3 = checkA.volumeMm3;
    overlap.volumeBMm3 = checkB.volumeMm3;
    const double areaB = checkB.areaMm2;
    const Vec3 direction = overlapShiftDirection();
    // Corefinement, exact, where the flux found no general position even
    // with B moved (not met on any reconstructed surface so far; kept
    // because it decides the same question another way).
    if (!likelyCoincideInPart(a, b)) {
        if (const std::optional<double> volume = intersectionVolume(a, b, {0, 0, 0})) {
            overlap.intersectionMm3 = *volume;
            overlap.method = "exact";
            return overlap;
        }
    }
    // Corefinement's constructions are exact: any shift does; these have
    // always been its.
    for (const double shiftMm : {1e-6, 1e-5, 1e-4}) {
        const std::optional<double> volume = intersectionVolume(a, b, shiftMm * direction);
        if (!volume) continue;
        overlap.intersectionMm3 = *volume;
        overlap.method = "exact, B shifted";
        overlap.shiftMm = shiftMm;
        overlap.intersectionBoundMm3 = areaB * shiftMm;
        return overlap;
    }
    throw std::runtime_error(
        "the intersection of the two solids could not be built, even with B shifted by up to "
        "1e-4 mm");
}

}  // namespace dfrecon
