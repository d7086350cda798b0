#include "simplify/CollapseBound.hpp"

#include <algorithm>
#include <cmath>

namespace dfrecon {

bool trianglesAfterCollapse(const TriMesh& mesh, TriMesh::HalfedgeHandle v0v1,
                            std::vector<NewTriangle>& out) {
    out.clear();
    const auto v0 = mesh.from_vertex_handle(v0v1), v1 = mesh.to_vertex_handle(v0v1);
    const TriMesh::FaceHandle fl = mesh.face_handle(v0v1), fr = mesh.opposite_face_handle(v0v1);
    for (auto f : mesh.vf_range(v0)) {
        if (f == fl || f == fr) continue;
        NewTriangle t;
        int k = 0;
        for (auto v : mesh.fv_range(f)) {
            const auto moved = v == v0 ? v1 : v;
            t.ids[std::size_t(k)] = std::uint32_t(moved.idx());
            t.p[k++] = toVec3(mesh.point(moved));
        }
        const Vec3 e0 = t.p[1] - t.p[0], e1 = t.p[2] - t.p[0], e2 = t.p[2] - t.p[1];
        const double longest2 = std::max({dot(e0, e0), dot(e1, e1), dot(e2, e2)});
        if (length(cross(e0, e1)) <= kSliverAreaRatio * longest2) return false;
        out.push_back(t);
    }
    return true;
}

double DeviationCache::bound(const NewTriangle& t, const TriangleBvh& original,
                             const DeviationLimits& limits) {
    constexpr std::uint32_t kIdLimit = 1u << 21;
    std::array<std::uint32_t, 3> ids = t.ids;
    if (ids[0] >= kIdLimit || ids[1] >= kIdLimit || ids[2] >= kIdLimit)
        return deviationBound(original, t.p[0], t.p[1], t.p[2], limits);
    std::sort(ids.begin(), ids.end());
    const std::uint64_t key =
        std::uint64_t(ids[0]) | std::uint64_t(ids[1]) << 21 | std::uint64_t(ids[2]) << 42;
    const auto found = bounds_.find(key);
    if (found != bounds_.end()) return found->second;
    const double d = deviationBound(original, t.p[0], t.p[1], t.p[2], limits);
    // Stored rounded up, so the cached value is still an upper bound.
    bounds_.emplace(key, std::nextafter(float(d), INFINITY));
    return d;
}

float surfaceDeviation(const std::vector<NewTriangle>& created, const TriangleBvh& original,
                       const DeviationLimits& limits, DeviationCache* cache) {
    double deviation = 0;
    for (const NewTriangle& t : created) {
        const double d = cache ? cache->bound(t, original, limits)
                               : deviationBound(original, t.p[0], t.p[1], t.p[2], limits);
        if (d > limits.limitMm) return -1;
        deviation = std::max(deviation, d);
    }
    return float(deviation);
}

}  // namespace dfrecon
