#include "geometry/TriangleSoup.hpp"

#include <algorithm>
#include <mutex>

namespace dfrecon {

TriangleSoup toTriangleSoup(const TriMesh& mesh) {
    TriangleSoup soup;
    for (auto v : mesh.vertices()) {
        const auto p = mesh.point(v);
        soup.points.push_back({p[0], p[1], p[2]});
    }
    for (auto f : mesh.faces()) {
        std::array<std::uint32_t, 3> t{};
        int k = 0;
        for (auto v : mesh.fv_range(f))
            if (k < 3) t[std::size_t(k++)] = std::uint32_t(v.idx());
        soup.triangles.push_back(t);
    }
    return soup;
}

void appendSoup(TriangleSoup& soup, const TriangleSoup& part) {
    const auto offset = std::uint32_t(soup.points.size());
    soup.points.insert(soup.points.end(), part.points.begin(), part.points.end());
    soup.triangles.reserve(soup.triangles.size() + part.triangles.size());
    for (const auto& t : part.triangles)
        soup.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

void removeUnusedPoints(TriangleSoup& soup) {
    constexpr std::uint32_t kUnused = 0xffffffffu;
    std::vector<std::uint32_t> index(soup.points.size(), kUnused);
    std::uint32_t count = 0;
    for (auto& t : soup.triangles)
        for (std::uint32_t& v : t) {
            if (index[v] == kUnused) index[v] = count++;
            v = index[v];
        }
    // Sized once: grown point by point, a surface of millions of points
    // would hold up to twice its size beside the old array.
    std::vector<Vec3> kept(count);
    for (std::size_t v = 0; v < soup.points.size(); ++v)
        if (index[v] != kUnused) kept[index[v]] = soup.points[v];
    soup.points = std::move(kept);
}

std::vector<std::uint32_t> idsWithoutUnusedFrom(const TriangleSoup& soup, std::size_t first) {
    std::vector<std::uint32_t> id(soup.points.size() - first, kUnusedPoint);
    for (const auto& t : soup.triangles)
        for (std::uint32_t v : t)
            if (v >= first) id[v - first] = 0;
    std::size_t kept = first;
    for (std::uint32_t& i : id)
        if (i != kUnusedPoint) i = std::uint32_t(kept++);
    return id;
}

void removeUnusedPointsFrom(TriangleSoup& soup, std::size_t first) {
    const std::vector<std::uint32_t> id = idsWithoutUnusedFrom(soup, first);
    std::size_t kept = first;  // the ids count up from `first` in order
    for (std::size_t i = 0; i < id.size(); ++i)
        if (id[i] != kUnusedPoint) soup.points[kept++] = soup.points[first + i];
    soup.points.resize(kept);
    soup.points.shrink_to_fit();
    soup.triangles.shrink_to_fit();
    for (auto& t : soup.triangles)
        for (std::uint32_t& v : t)
            if (v >= first) v = id[v - first];
}

namespace {

// OpenMesh's error stream is one process-wide object, made on first use:
// made here at load, before any worker thread (two threads making it at
// once made two, and leaked one), and silenced while any thread converts a
// soup (a count, so one thread's enable does not unmute another's loop).
std::mutex quietMutex;
int quietSections = 0;
[[maybe_unused]] const bool openMeshErrorStreamMade = (omerr(), true);

struct QuietOpenMeshErrors {
    QuietOpenMeshErrors() {
        const std::lock_guard<std::mutex> lock(quietMutex);
        if (quietSections++ == 0) omerr().disable();
    }
    ~QuietOpenMeshErrors() {
        const std::lock_guard<std::mutex> lock(quietMutex);
        if (--quietSections == 0) omerr().enable();
    }
    QuietOpenMeshErrors(const QuietOpenMeshErrors&) = delete;
    QuietOpenMeshErrors& operator=(const QuietOpenMeshErrors&) = delete;
};

}  // namespace

namespace {

// soupOfTriangles over triangle(k) for k < count.
template <class TriangleAt>
TriangleSoup soupOf(const TriangleSoup& soup, std::size_t count, TriangleAt triangle) {
    // Sorted ids, not a table over all points: a surface's parts are
    // checked one after another, each a small share of it.
    std::vector<std::uint32_t> ids;
    ids.reserve(3 * count);
    for (std::size_t k = 0; k < count; ++k) {
        const auto& tri = soup.triangles[triangle(k)];
        ids.insert(ids.end(), tri.begin(), tri.end());
    }
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    TriangleSoup part;
    part.points.reserve(ids.size());
    for (std::uint32_t v : ids) part.points.push_back(soup.points[v]);
    part.triangles.reserve(count);
    for (std::size_t k = 0; k < count; ++k) {
        auto tri = soup.triangles[triangle(k)];
        for (std::uint32_t& v : tri)
            v = std::uint32_t(std::lower_bound(ids.begin(), ids.end(), v) - ids.begin());
        part.triangles.push_back(tri);
    }
    return part;
}

}  // namespace

TriangleSoup soupOfTriangles(const TriangleSoup& soup, std::size_t first, std::size_t last) {
    return soupOf(soup, last - first, [&](std::size_t k) { return first + k; });
}

TriangleSoup soupOfTriangles(const TriangleSoup& soup, const std::vector<std::size_t>& subset) {
    return soupOf(soup, subset.size(), [&](std::size_t k) { return subset[k]; });
}

TriMesh toTriMesh(const TriangleSoup& soup, std::size_t* refusedFaces) {
    TriMesh mesh;
    // A closed surface has 3/2 edges per face: reserved, OpenMesh's arrays
    // are not copied as they grow.
    mesh.reserve(soup.points.size(), soup.triangles.size() * 3 / 2, soup.triangles.size());
    std::vector<TriMesh::VertexHandle> vertices;
    vertices.reserve(soup.points.size());
    for (const Vec3& p : soup.points) vertices.push_back(mesh.add_vertex({p.x, p.y, p.z}));
    std::size_t refused = 0;
    // OpenMesh reports each refused face on stderr; the count says it once.
    const QuietOpenMeshErrors quiet;
    for (const auto& t : soup.triangles) {
        // OpenMesh asserts on a face that repeats a vertex; it is refused too.
        const bool repeats = t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
        if (repeats || !mesh.add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]).is_valid())
            ++refused;
    }
    if (refusedFaces) *refusedFaces = refused;
    return mesh;
}

namespace {

// GCC 12.2 at -O3 vectorizes a point's x and y as one pair and drops their
// double -> float -> double round trip (in the loop's scalar tail only z
// was rounded): a volatile float keeps every conversion.
double toFloatPrecision(double v) {
    volatile float rounded = static_cast<float>(v);
    return rounded;
}

}  // namespace

void roundPointsToFloat(TriangleSoup& soup) {
    for (Vec3& p : soup.points)
        p = {toFloatPrecision(p.x), toFloatPrecision(p.y), toFloatPrecision(p.z)};
}

void toPatient(TriangleSoup& soup, const PlaneFrame& frame) {
    if (frame.isIdentity()) return;
    for (Vec3& p : soup.points) p = frame.toPatient(p);
}

}  // namespace dfrecon
