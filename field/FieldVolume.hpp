#pragma once
// The 3D field as a dense volume for export: x and y on the field's pixels,
// z resampled to even steps (linear between layers), covering the virtual
// end layers so caps are inside.
#include "field/DistanceField3D.hpp"
#include "geometry/VolumeGrid.hpp"

namespace dfrecon {

/// Samples `field` every `zStepMm` from its first layer to its last.
/// O(pixels · samples).
DenseDistanceVolume resampleAlongZ(const DistanceField3D& field, double zStepMm);

}  // namespace dfrecon
