#include "recon/SurfaceBuilder.hpp"

#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace dfrecon {

TriangleSoup SurfaceBuilder::trianglesSince(std::size_t first) const {
    TriangleSoup piece;
    std::unordered_map<std::uint32_t, std::uint32_t> local;
    for (std::size_t t = first; t < soup_.triangles.size(); ++t) {
        std::array<std::uint32_t, 3> tri{};
        for (std::size_t k = 0; k < 3; ++k) {
            const std::uint32_t v = soup_.triangles[t][k];
            auto [it, fresh] = local.emplace(v, std::uint32_t(piece.points.size()));
            if (fresh) piece.points.push_back(soup_.points[v]);
            tri[k] = it->second;
        }
        piece.triangles.push_back(tri);
    }
    return piece;
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

SurfacePart SurfaceBuilder::takePart(std::size_t sharedPoints) {
    SurfacePart part;
    part.sharedPoints = sharedPoints;
    part.points.assign(soup_.points.begin() + std::ptrdiff_t(sharedPoints), soup_.points.end());
    soup_.points.resize(sharedPoints);
    part.triangles = std::exchange(soup_.triangles, {});
    part.pieces = std::exchange(pieces_, {});
    part.lofts = std::exchange(lofts_, {});
    part.cleanGroups = std::exchange(cleanGroups_, {});
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
