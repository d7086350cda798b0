#include "compare/OverlapVolume.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>

#include <stdexcept>

#include "geometry/MeshCheck.hpp"

namespace dfrecon {

namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

Mesh toCgal(const TriangleSoup& soup) {
    Mesh mesh;
    std::vector<Mesh::Vertex_index> vertices;
    vertices.reserve(soup.points.size());
    for (const Vec3& p : soup.points) vertices.push_back(mesh.add_vertex({p.x, p.y, p.z}));
    for (const auto& t : soup.triangles)
        if (mesh.add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]) == Mesh::null_face())
            throw std::invalid_argument("a triangle could not be added (not manifold)");
    return mesh;
}

double volumeOf(const Mesh& mesh) {
    return mesh.number_of_faces() == 0
               ? 0.0
               : CGAL::to_double(CGAL::Polygon_mesh_processing::volume(mesh));
}

}  // namespace

double Overlap::dice() const {
    const double sum = volumeAMm3 + volumeBMm3;
    return sum > 0 ? 2 * intersectionMm3 / sum : 1.0;
}

double Overlap::jaccard() const {
    const double all = unionMm3();
    return all > 0 ? intersectionMm3 / all : 1.0;
}

Overlap overlapOf(const TriangleSoup& a, const TriangleSoup& b) {
    for (const TriangleSoup* soup : {&a, &b})
        if (!checkMesh(*soup).validSolid())
            throw std::invalid_argument(std::string("surface ") + (soup == &a ? "A" : "B") +
                                        " is not a valid closed solid (dfrecon check says where)");
    Mesh meshA = toCgal(a), meshB = toCgal(b), meet;
    Overlap overlap;
    overlap.volumeAMm3 = volumeOf(meshA);
    overlap.volumeBMm3 = volumeOf(meshB);
    // Corefinement refines both inputs along their intersection; the copies
    // above are ours to change.
    if (!CGAL::Polygon_mesh_processing::corefine_and_compute_intersection(meshA, meshB, meet))
        throw std::runtime_error("the intersection of the two solids is not a manifold solid");
    overlap.intersectionMm3 = volumeOf(meet);
    return overlap;
}

}  // namespace dfrecon
