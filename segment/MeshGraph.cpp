#include "segment/MeshGraph.hpp"

#include <stdexcept>
#include <string>

namespace dfrecon {

MeshGraph::MeshGraph(std::vector<Vec3> points, std::vector<std::array<int, 3>> triangles)
    : points_(std::move(points)), triangles_(std::move(triangles)) {
    const int n = int(points_.size());
    vertexTriangleFirst_.assign(std::size_t(n) + 1, 0);
    for (std::size_t t = 0; t < triangles_.size(); ++t) {
        const auto& tri = triangles_[t];
        for (int v : tri)
            if (v < 0 || v >= n)
                throw std::invalid_argument("triangle " + std::to_string(t) + " has vertex index " +
                                            std::to_string(v) + " out of range");
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
            throw std::invalid_argument("triangle " + std::to_string(t) + " repeats a vertex");
        for (int v : tri) ++vertexTriangleFirst_[std::size_t(v) + 1];
    }
    for (int v = 0; v < n; ++v)
        vertexTriangleFirst_[std::size_t(v) + 1] += vertexTriangleFirst_[std::size_t(v)];
    vertexTriangles_.resize(triangles_.size() * 3);
    std::vector<int> fill(vertexTriangleFirst_.begin(), vertexTriangleFirst_.end() - 1);
    for (std::size_t t = 0; t < triangles_.size(); ++t)
        for (int v : triangles_[t]) vertexTriangles_[std::size_t(fill[std::size_t(v)]++)] = int(t);

    // Neighbours: the other triangle around the edge's first vertex that also
    // has its second vertex. Scanning one vertex's triangles is O(degree).
    neighbours_.assign(triangles_.size(), {-1, -1, -1});
    for (int t = 0; t < triangleCount(); ++t) {
        const auto& tri = triangles_[std::size_t(t)];
        for (int corner = 0; corner < 3; ++corner) {
            const int u = tri[std::size_t((corner + 1) % 3)],
                      w = tri[std::size_t((corner + 2) % 3)];
            int found = -1;
            for (int other : trianglesAround(u)) {
                if (other == t || cornerOf(other, w) < 0) continue;
                if (found >= 0)
                    throw std::invalid_argument("edge (" + std::to_string(u) + ", " +
                                                std::to_string(w) +
                                                ") has more than two triangles (not a manifold)");
                found = other;
            }
            neighbours_[std::size_t(t)][std::size_t(corner)] = found;
        }
    }
}

MeshGraph MeshGraph::fromSoup(const TriangleSoup& soup) {
    std::vector<std::array<int, 3>> triangles;
    triangles.reserve(soup.triangles.size());
    for (const auto& t : soup.triangles) triangles.push_back({int(t[0]), int(t[1]), int(t[2])});
    return MeshGraph(soup.points, std::move(triangles));
}

MeshGraph MeshGraph::fromMesh(const TriMesh& mesh) {
    std::vector<Vec3> points(mesh.n_vertices());
    for (auto v : mesh.vertices()) {
        const auto& p = mesh.point(v);
        points[std::size_t(v.idx())] = {p[0], p[1], p[2]};
    }
    std::vector<std::array<int, 3>> triangles(mesh.n_faces());
    for (auto f : mesh.faces()) {
        int k = 0;
        for (auto v : mesh.fv_range(f)) {
            if (k == 3)
                throw std::invalid_argument("face " + std::to_string(f.idx()) +
                                            " is not a triangle");
            triangles[std::size_t(f.idx())][std::size_t(k++)] = v.idx();
        }
    }
    return MeshGraph(std::move(points), std::move(triangles));
}

int MeshGraph::cornerOf(int t, int v) const {
    const auto& tri = triangles_[std::size_t(t)];
    return tri[0] == v ? 0 : tri[1] == v ? 1 : tri[2] == v ? 2 : -1;
}

double MeshGraph::triangleArea(int t) const {
    const auto& tri = triangles_[std::size_t(t)];
    const Vec3 a = point(tri[0]);
    return 0.5 * length(cross(point(tri[1]) - a, point(tri[2]) - a));
}

double MeshGraph::totalArea() const {
    double area = 0;
    for (int t = 0; t < triangleCount(); ++t) area += triangleArea(t);
    return area;
}

std::vector<double> MeshGraph::vertexAreas() const {
    std::vector<double> areas(points_.size(), 0.0);
    for (int t = 0; t < triangleCount(); ++t) {
        const double third = triangleArea(t) / 3;
        for (int v : triangles_[std::size_t(t)]) areas[std::size_t(v)] += third;
    }
    return areas;
}

double MeshGraph::meanEdgeLength() const {
    double sum = 0;
    std::size_t count = 0;
    for (int t = 0; t < triangleCount(); ++t) {
        const auto& tri = triangles_[std::size_t(t)];
        for (int corner = 0; corner < 3; ++corner) {
            // Count an interior edge from the triangle with the smaller index.
            const int other = neighbours_[std::size_t(t)][std::size_t(corner)];
            if (other >= 0 && other < t) continue;
            sum += length(point(tri[std::size_t((corner + 1) % 3)]) -
                          point(tri[std::size_t((corner + 2) % 3)]));
            ++count;
        }
    }
    return count == 0 ? 0.0 : sum / double(count);
}

int MeshGraph::boundaryEdgeCount() const {
    int count = 0;
    for (const auto& n : neighbours_)
        for (int other : n) count += other < 0 ? 1 : 0;
    return count;
}

}  // namespace dfrecon
