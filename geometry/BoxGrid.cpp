#include "geometry/BoxGrid.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace dfrecon {

BoxGrid::BoxGrid(std::vector<Box3> boxes, double cellMm)
    : boxes_(std::move(boxes)), cellMm_(cellMm), seen_(boxes_.size(), 0) {
    if (!(cellMm > 0)) throw std::invalid_argument("BoxGrid: cell size must be > 0");
    for (std::size_t i = 0; i < boxes_.size(); ++i)
        forEachCell(boxes_[i], [&](std::uint64_t key) { cells_[key].push_back(std::uint32_t(i)); });
}

BoxGrid BoxGrid::sizedToBoxes(std::vector<Box3> boxes) {
    std::vector<double> extents(boxes.size());
    Box3 scene;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const Vec3 e = boxes[i].hi - boxes[i].lo;
        extents[i] = std::max({e.x, e.y, e.z});
        scene.add(boxes[i]);
    }
    double cellMm = 1e-9;
    if (!boxes.empty()) {
        const auto middle = extents.begin() + std::ptrdiff_t(extents.size() / 2);
        std::nth_element(extents.begin(), middle, extents.end());
        const Vec3 size = scene.hi - scene.lo;
        cellMm = std::max({cellMm, *middle, size.x / 64, size.y / 64, size.z / 64});
    }
    return BoxGrid(std::move(boxes), cellMm);
}

}  // namespace dfrecon
