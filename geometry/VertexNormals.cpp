#include "geometry/VertexNormals.hpp"

namespace dfrecon {

void setVertexNormals(TriMesh& mesh) {
    mesh.request_vertex_normals();
    for (const auto v : mesh.vertices()) {
        TriMesh::Normal sum(0, 0, 0);
        // The circulator's order is the one calc_vertex_normal_fast sums in.
        for (const auto f : mesh.vf_range(v)) sum += mesh.calc_face_normal(f);
        const double length = sum.norm();
        if (length != 0.0) sum *= 1.0 / length;
        mesh.set_normal(v, sum);
    }
}

}  // namespace dfrecon
