#pragma once
// The 3D distance field of a reconstructed ROI (reconstruction paper §6.1):
// the slices' exact 2D signed fields propagated along z. Its distance is the
// in-slice Euclidean distance plus |Δz| (a double cone as unit sphere), never
// less than the Euclidean one, so bounds read from it are conservative; its
// zero set between layers is where linear interpolation of the 2D fields
// puts it (the Levin surface the reconstruction follows).
#include <vector>

#include "cl/Runtime.hpp"
#include "field/SliceFields.hpp"

namespace dfrecon {

/// Layers on the slices' grid, stored layer after layer, each row-major.
/// Beyond each end slice come two virtual layers: the cap plane half a
/// spacing out (the flat caps' planning-system convention: zero over the end
/// contours' region, their in-slice distance outside) and one more half a
/// spacing further, so the surface's outside is covered.
struct DistanceField3D {
    SliceGrid grid;
    std::vector<double> zMm;        // one per layer, increasing (gaps may differ)
    std::vector<float> distanceMm;  // signed: < 0 inside

    std::size_t layerCount() const { return zMm.size(); }
    std::size_t index(std::size_t layer, int i, int j) const {
        return layer * grid.pixelCount() + std::size_t(j) * std::size_t(grid.width) +
               std::size_t(i);
    }
};

/// The 2D fields as layers, with the virtual end layers and empty slices
/// (+inf) replaced by a far positive value. `endSpacingMm` is the spacing
/// assumed beyond a single slice. O(layers · pixels).
DistanceField3D layersFromSlices(const SliceFields& fields, double endSpacingMm);

/// Propagates in place with the propagate_z kernel (kernels/distance_3d.cl).
/// O(layers · pixels), one work-item per pixel column.
void propagateAlongZ(ocl::Runtime& runtime, DistanceField3D& field);

/// The plain C++ reference of propagateAlongZ; the same arithmetic, so the
/// two agree to float rounding.
void propagateAlongZReference(DistanceField3D& field);

/// The field at a point by trilinear interpolation (bilinear in the layer,
/// linear between layers; clamped to the grid and layer range).
double sampleField(const DistanceField3D& field, double xMm, double yMm, double zMm);

}  // namespace dfrecon
