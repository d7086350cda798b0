#include "recon/SurfaceBuilder.hpp"

namespace dfrecon {

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
