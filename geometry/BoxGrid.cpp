#include "geometry/BoxGrid.hpp"

#include <stdexcept>
#include <utility>

namespace dfrecon {

BoxGrid::BoxGrid(std::vector<Box3> boxes, double cellMm)
    : boxes_(std::move(boxes)), cellMm_(cellMm), seen_(boxes_.size(), 0) {
    if (!(cellMm > 0)) throw std::invalid_argument("BoxGrid: cell size must be > 0");
    for (std::size_t i = 0; i < boxes_.size(); ++i)
        forEachCell(boxes_[i], [&](std::uint64_t key) { cells_[key].push_back(std::uint32_t(i)); });
}

}  // namespace dfrecon
