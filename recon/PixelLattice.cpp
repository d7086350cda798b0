#include "recon/PixelLattice.hpp"

#include <cmath>
#include <limits>

namespace dfrecon {

bool followsPixelLattice(const std::vector<Slice>& slices) {
    double step = std::numeric_limits<double>::infinity();
    std::size_t points = 0;
    for (const Slice& slice : slices)
        for (const Polygon& contour : slice.contours)
            for (std::size_t k = 0; k < contour.size(); ++k) {
                const Point2 d = contour[(k + 1) % contour.size()] - contour[k];
                for (const double delta : {std::abs(d.x), std::abs(d.y)})
                    if (delta > 1e-6) step = std::min(step, delta);
                ++points;
            }
    if (points < 64 || !(step >= 0.05) || !std::isfinite(step)) return false;
    Point2 origin{};
    for (const Slice& slice : slices)
        if (!slice.contours.empty() && !slice.contours.front().empty()) {
            origin = slice.contours.front().front();
            break;
        }
    const auto onLattice = [&](double offset) {
        const double r = offset / step;
        return std::abs(r - std::round(r)) <= 1e-3;
    };
    for (const Slice& slice : slices)
        for (const Polygon& contour : slice.contours)
            for (const Point2 p : contour)
                if (!onLattice(p.x - origin.x) || !onLattice(p.y - origin.y)) return false;
    return true;
}

}  // namespace dfrecon
