#include "field/SurfaceScene.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <utility>

#include "geometry/MeshCheck.hpp"

namespace dfrecon {

namespace {

Vec3 normalized(Vec3 v) {
    const double l = length(v);
    return l > 0 ? (1 / l) * v : Vec3{};
}

// The angle between u and v, robust for tiny angles (atan2 of |u×v|, u·v).
double angleBetween(Vec3 u, Vec3 v) {
    return std::atan2(length(cross(u, v)), dot(u, v));
}

std::vector<std::array<Vec3, 7>> pseudoNormals(const TriangleSoup& soup, bool flip) {
    const std::size_t count = soup.triangles.size();
    std::vector<Vec3> faceNormal(count), vertexNormal(soup.points.size());
    std::map<std::pair<std::uint32_t, std::uint32_t>, Vec3> edgeNormal;
    for (std::size_t t = 0; t < count; ++t) {
        const auto& tri = soup.triangles[t];
        const Vec3 p[3] = {soup.points[tri[0]], soup.points[tri[1]], soup.points[tri[2]]};
        Vec3 n = normalized(cross(p[1] - p[0], p[2] - p[0]));
        if (flip) n = -1.0 * n;
        faceNormal[t] = n;
        for (int k = 0; k < 3; ++k) {
            const Vec3 prev = p[(k + 2) % 3] - p[k], next = p[(k + 1) % 3] - p[k];
            vertexNormal[tri[std::size_t(k)]] =
                vertexNormal[tri[std::size_t(k)]] + angleBetween(next, prev) * n;
            const std::uint32_t u = tri[std::size_t(k)], v = tri[std::size_t(k + 1) % 3];
            Vec3& e = edgeNormal[{std::min(u, v), std::max(u, v)}];
            e = e + n;
        }
    }
    std::vector<std::array<Vec3, 7>> normals(count);
    for (std::size_t t = 0; t < count; ++t) {
        const auto& tri = soup.triangles[t];
        auto edge = [&](int k) {
            const std::uint32_t u = tri[std::size_t(k)], v = tri[std::size_t(k + 1) % 3];
            return edgeNormal[{std::min(u, v), std::max(u, v)}];
        };
        normals[t] = {vertexNormal[tri[0]],
                      vertexNormal[tri[1]],
                      vertexNormal[tri[2]],
                      edge(0),
                      edge(1),
                      edge(2),
                      faceNormal[t]};
    }
    return normals;
}

}  // namespace

SurfaceScene::SurfaceScene(std::vector<TriangleSoup> objects, std::vector<std::string> names) {
    for (std::size_t i = 0; i < objects.size(); ++i) {
        if (objects[i].triangles.empty())
            throw std::invalid_argument("surface scene: object " + std::to_string(i) +
                                        " has no triangles");
        auto object = std::make_unique<Object>();
        object->name = i < names.size() ? names[i] : "object" + std::to_string(i);
        object->soup = std::move(objects[i]);
        object->bvh = std::make_unique<TriangleBvh>(object->soup);
        const MeshCheckReport check = checkMesh(object->soup);
        object->closed = check.watertight();
        // Signs need outward normals; a closed mesh whose faces point
        // inwards encloses negative volume.
        object->pseudoNormals = pseudoNormals(object->soup, object->closed && check.volumeMm3 < 0);
        objects_.push_back(std::move(object));
    }
}

std::size_t SurfaceScene::triangleCount() const {
    std::size_t count = 0;
    for (const auto& o : objects_) count += o->soup.triangles.size();
    return count;
}

}  // namespace dfrecon
