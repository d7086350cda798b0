#include "field/SurfaceScene.hpp"

#include <algorithm>
#include <cstdint>
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
    // Each triangle's edge k is one entry; sorting by edge brings the two
    // uses of an edge together (a map per edge cost most of a large scene).
    struct EdgeUse {
        std::uint64_t edge;
        std::uint32_t triangle, k;
    };
    std::vector<EdgeUse> uses;
    uses.reserve(3 * count);
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
            uses.push_back({std::uint64_t(std::min(u, v)) << 32 | std::max(u, v), std::uint32_t(t),
                            std::uint32_t(k)});
        }
    }
    std::sort(uses.begin(), uses.end(),
              [](const EdgeUse& a, const EdgeUse& b) { return a.edge < b.edge; });
    std::vector<std::array<Vec3, 7>> normals(count);
    for (std::size_t first = 0; first < uses.size();) {
        std::size_t last = first;
        Vec3 sum;
        for (; last < uses.size() && uses[last].edge == uses[first].edge; ++last)
            sum = sum + faceNormal[uses[last].triangle];
        for (std::size_t i = first; i < last; ++i) normals[uses[i].triangle][3 + uses[i].k] = sum;
        first = last;
    }
    for (std::size_t t = 0; t < count; ++t) {
        const auto& tri = soup.triangles[t];
        for (int k = 0; k < 3; ++k) normals[t][std::size_t(k)] = vertexNormal[tri[std::size_t(k)]];
        normals[t][6] = faceNormal[t];
    }
    return normals;
}

}  // namespace

namespace {

std::string objectName(const std::vector<std::string>& names, std::size_t i) {
    return i < names.size() ? names[i] : "object" + std::to_string(i);
}

}  // namespace

SurfaceScene::SurfaceScene(std::vector<TriangleSoup> objects, std::vector<std::string> names) {
    for (std::size_t i = 0; i < objects.size(); ++i) {
        const MeshCheckReport check = checkMesh(objects[i]);
        // Signs need outward normals; a closed mesh whose faces point
        // inwards encloses negative volume.
        add(std::move(objects[i]), objectName(names, i), check.watertight(),
            check.watertight() && check.volumeMm3 < 0);
    }
}

SurfaceScene::SurfaceScene(std::vector<TriangleSoup> objects, std::vector<std::string> names,
                           KnownValidSolids) {
    for (std::size_t i = 0; i < objects.size(); ++i)
        add(std::move(objects[i]), objectName(names, i), true, false);
}

void SurfaceScene::add(TriangleSoup soup, std::string name, bool closed, bool flip) {
    if (soup.triangles.empty())
        throw std::invalid_argument("surface scene: object " + std::to_string(objects_.size()) +
                                    " has no triangles");
    auto object = std::make_unique<Object>();
    object->name = std::move(name);
    object->soup = std::move(soup);
    object->bvh = std::make_unique<TriangleBvh>(object->soup);
    object->closed = closed;
    object->pseudoNormals = pseudoNormals(object->soup, flip);
    objects_.push_back(std::move(object));
}

std::size_t SurfaceScene::triangleCount() const {
    std::size_t count = 0;
    for (const auto& o : objects_) count += o->soup.triangles.size();
    return count;
}

}  // namespace dfrecon
