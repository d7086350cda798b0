#include "recon/SurfaceBuilder.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace dfrecon {

TriangleSoup SurfaceBuilder::trianglesSince(std::size_t first) const {
    return soupOfTriangles(soup_, first, soup_.triangles.size());
}

void SurfaceBuilder::dropPieces(const std::vector<bool>& drop) {
    std::size_t kept = 0;
    for (std::size_t t = 0; t < soup_.triangles.size(); ++t) {
        if (pieces_[t] < drop.size() && drop[pieces_[t]]) continue;
        soup_.triangles[kept] = soup_.triangles[t];
        lofts_[kept] = lofts_[t];
        cleanGroups_[kept] = cleanGroups_[t];
        pieces_[kept++] = pieces_[t];
    }
    truncateTriangles(kept);
}

namespace {

/// Room for `extra` more elements, growing by half at least (vector's own
/// growth doubles: a builder of millions of triangles then holds up to
/// twice what it needs, and three times its size while it moves).
template <class Vector>
void reserveFor(Vector& v, std::size_t extra) {
    if (v.capacity() - v.size() >= extra) return;
    v.reserve(std::max(v.size() + extra, v.size() + v.size() / 2));
}

/// A copy of `v` with no spare capacity (a part's arrays grew by doubling).
template <class Vector>
Vector exactCopy(Vector&& v) {
    Vector exact(std::forward<Vector>(v));
    exact.shrink_to_fit();
    return exact;
}

}  // namespace

SurfacePart SurfaceBuilder::takePart(std::size_t sharedPoints) {
    // Only the new points a triangle uses go along, in their order: the
    // intermediate contours of sub-slabs solved again leave points behind
    // (a third of the head CT bone's), which the builder that collects the
    // parts would otherwise hold to the end.
    // (removeUnusedPointsFrom would also copy the shared points, once a slab.)
    const std::vector<std::uint32_t> id = idsWithoutUnusedFrom(soup_, sharedPoints);
    SurfacePart part;
    part.sharedPoints = sharedPoints;
    part.points.reserve(std::size_t(
        std::count_if(id.begin(), id.end(), [](std::uint32_t i) { return i != kUnusedPoint; })));
    for (std::size_t i = 0; i < id.size(); ++i)
        if (id[i] != kUnusedPoint) part.points.push_back(soup_.points[sharedPoints + i]);
    soup_.points.resize(sharedPoints);
    part.triangles = exactCopy(std::exchange(soup_.triangles, {}));
    for (auto& t : part.triangles)
        for (std::uint32_t& v : t)
            if (v >= sharedPoints) v = id[v - sharedPoints];
    part.pieces = exactCopy(std::exchange(pieces_, {}));
    part.lofts = exactCopy(std::exchange(lofts_, {}));
    part.cleanGroups = exactCopy(std::exchange(cleanGroups_, {}));
    part.cleanGroupCount = std::exchange(lastCleanGroup_, 0);
    return part;
}

SurfaceBuilder::Released SurfaceBuilder::release() {
    Released released{std::exchange(soup_, {}), std::exchange(pieces_, {}),
                      std::exchange(lofts_, {})};
    cleanGroups_ = {};
    lastCleanGroup_ = 0;
    return released;
}

void SurfaceBuilder::appendPart(SurfacePart&& part) {
    if (part.sharedPoints > soup_.points.size())
        throw std::logic_error("SurfaceBuilder::appendPart: part built on more points");
    const auto offset = std::uint32_t(soup_.points.size() - part.sharedPoints);
    reserveFor(soup_.points, part.points.size());
    reserveFor(soup_.triangles, part.triangles.size());
    reserveFor(pieces_, part.pieces.size());
    reserveFor(lofts_, part.lofts.size());
    reserveFor(cleanGroups_, part.cleanGroups.size());
    soup_.points.insert(soup_.points.end(), part.points.begin(), part.points.end());
    for (std::array<std::uint32_t, 3> t : part.triangles) {
        for (std::uint32_t& v : t)
            if (v >= part.sharedPoints) v += offset;
        soup_.triangles.push_back(t);
    }
    pieces_.insert(pieces_.end(), part.pieces.begin(), part.pieces.end());
    lofts_.insert(lofts_.end(), part.lofts.begin(), part.lofts.end());
    for (std::uint32_t group : part.cleanGroups)
        cleanGroups_.push_back(group == 0 ? 0 : group + lastCleanGroup_);
    lastCleanGroup_ += part.cleanGroupCount;
    part = {};
}

Layer makeLayer(SurfaceBuilder& builder, double zMm, std::vector<Polygon> contours) {
    Layer layer;
    layer.zMm = zMm;
    layer.contours = std::move(contours);
    for (const Polygon& contour : layer.contours) {
        std::vector<std::uint32_t> ids;
        ids.reserve(contour.size());
        for (Point2 p : contour) ids.push_back(builder.addVertex(p, zMm));
        layer.vertexIds.push_back(std::move(ids));
    }
    return layer;
}

}  // namespace dfrecon
