#include "recon/IsoContours.hpp"

#include <algorithm>

#include <stdexcept>

#include "geometry/IsoLines.hpp"

namespace dfrecon {

std::vector<Polygon> zeroIsolines(const std::vector<float>& values, const SliceGrid& grid) {
    if (values.size() != grid.pixelCount())
        throw std::invalid_argument("zeroIsolines: field size does not match the grid");
    // Sample (i, j) at the pixel centre origin + (i + ½)·pixelMm, the same
    // expression as SliceGrid::pixelCentre, so crossings round identically.
    SampleLattice lattice;
    lattice.originMm = grid.originMm;
    lattice.stepMm = {grid.pixelMm, grid.pixelMm};
    lattice.indexOffset = {0.5, 0.5};
    // Field values are millimetres, so the zero nudge scales with the pixel.
    return negativeRegionBorders(values, grid.width, grid.height, lattice,
                                 float(1e-6 * grid.pixelMm));
}

std::vector<Polygon> isolinesEnclosing(const std::vector<float>& values, const SliceGrid& grid,
                                       const EnclosedArea& target) {
    const double targetAreaMm2 = target.areaMm2, maxLevelMm = target.maxLevelMm;
    if (target.within && target.within->size() != values.size())
        throw std::invalid_argument("isolinesEnclosing: bound size does not match the field");
    std::vector<Polygon> zero = zeroIsolines(values, grid);
    if (zero.empty() || !(maxLevelMm > 0) || netArea(zero) >= 0.99 * targetAreaMm2) return zero;
    auto atLevel = [&](double level) {
        std::vector<float> shifted(values);
        for (std::size_t k = 0; k < shifted.size(); ++k) {
            shifted[k] -= float(level);
            if (target.within) shifted[k] = std::max(shifted[k], (*target.within)[k]);
        }
        return zeroIsolines(shifted, grid);
    };
    std::vector<Polygon> high = atLevel(maxLevelMm);
    if (netArea(high) <= targetAreaMm2) return high;
    // {values < c} grows with c: bisection on the level, keeping the lower
    // end's isolines (never more than the target, within 1 % of it).
    double lo = 0, hi = maxLevelMm;
    std::vector<Polygon> best = std::move(zero);
    for (int step = 0; step < 12; ++step) {
        const double mid = 0.5 * (lo + hi);
        std::vector<Polygon> at = atLevel(mid);
        const double area = netArea(at);
        if (area > targetAreaMm2) {
            hi = mid;
        } else {
            lo = mid;
            best = std::move(at);
            if (area >= 0.99 * targetAreaMm2) break;
        }
    }
    return best;
}

}  // namespace dfrecon
