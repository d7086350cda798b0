#include "recon/SliceGrid.hpp"

#include <cmath>
#include <stdexcept>

namespace dfrecon {

SliceGrid gridAround(const Box2& box, double pixelMm, int marginPx) {
    if (!(pixelMm > 0) || box.empty())
        throw std::invalid_argument("gridAround: empty box or pixel");
    SliceGrid grid;
    grid.pixelMm = pixelMm;
    grid.originMm = {box.min.x - marginPx * pixelMm, box.min.y - marginPx * pixelMm};
    grid.width = int(std::ceil((box.max.x - box.min.x) / pixelMm)) + 2 * marginPx + 1;
    grid.height = int(std::ceil((box.max.y - box.min.y) / pixelMm)) + 2 * marginPx + 1;
    return grid;
}

}  // namespace dfrecon
