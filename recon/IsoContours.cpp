#include "recon/IsoContours.hpp"

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

}  // namespace dfrecon
