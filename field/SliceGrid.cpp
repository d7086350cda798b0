#include "field/SliceGrid.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

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

SliceGrid windowOf(const SliceGrid& grid, const Box2& box, int marginPx) {
    SliceGrid window = grid;
    if (box.empty()) {
        window.width = window.height = 0;
        return window;
    }
    // Pixel index ranges whose centres reach the box plus the margin.
    auto first = [&](double lo, double origin, int size) {
        return std::clamp(int(std::floor((lo - origin) / grid.pixelMm - 0.5)) - marginPx, 0, size);
    };
    auto last = [&](double hi, double origin, int size) {
        return std::clamp(int(std::ceil((hi - origin) / grid.pixelMm - 0.5)) + marginPx + 1, 0,
                          size);
    };
    const int i0 = first(box.min.x, grid.originMm.x, grid.width);
    const int i1 = last(box.max.x, grid.originMm.x, grid.width);
    const int j0 = first(box.min.y, grid.originMm.y, grid.height);
    const int j1 = last(box.max.y, grid.originMm.y, grid.height);
    window.originMm = {grid.originMm.x + i0 * grid.pixelMm, grid.originMm.y + j0 * grid.pixelMm};
    window.width = std::max(0, i1 - i0);
    window.height = std::max(0, j1 - j0);
    return window;
}

SliceGrid gridForSlices(const std::vector<Slice>& slices, double pixelMm, int gridPixels) {
    Box2 box;
    for (const Slice& slice : slices)
        for (const Polygon& contour : slice.contours)
            for (Point2 p : contour) box.add(p);
    if (box.empty()) throw std::invalid_argument("no contours to place a grid around");
    const double extent = std::max(box.max.x - box.min.x, box.max.y - box.min.y);
    const bool chosen = !(pixelMm > 0);
    if (chosen) {
        // Longest side: extent/pixel + 1 + 2·margin pixels = gridPixels.
        pixelMm = extent > 0 ? extent / std::max(1, gridPixels - 1 - 2 * kGridMarginPx) : 1.0;
    }
    // Streams write numbers as %g: 1e-09 mm, not std::to_string's 0.000000.
    std::ostringstream problem;
    if (extent / pixelMm > 16384) {
        problem << "pixel size " << pixelMm << " mm gives a grid over 16384 pixels a side";
        throw std::invalid_argument(problem.str());
    }
    const auto pixelsInAll = [&](double pixel) {
        return double(gridAround(box, pixel, kGridMarginPx).pixelCount()) * double(slices.size());
    };
    // Pixels fall with the square of the pixel size, or slower (the margin):
    // grow by the root, at least by 5 %, until the slices fit.
    double fitting = pixelMm;
    while (pixelsInAll(fitting) > double(kMaxRoiFieldPixels))
        fitting *= std::max(1.05, std::sqrt(pixelsInAll(fitting) / double(kMaxRoiFieldPixels)));
    if (fitting > pixelMm && !chosen) {
        problem << "pixel size " << pixelMm << " mm gives " << slices.size() << " planes over "
                << kMaxRoiFieldPixels
                << " field pixels in all, more than memory allows; the smallest that fits is "
                << fitting << " mm";
        throw std::invalid_argument(problem.str());
    }
    return gridAround(box, fitting, kGridMarginPx);
}

}  // namespace dfrecon
