#pragma once
// Sampled volumes as raw little-endian arrays with a detached NRRD header
// (.nhdr), which 3D Slicer, ParaView and ITK/SimpleITK open directly.
#include <cstdint>
#include <string>
#include <vector>

namespace dfrecon {

struct RawVolumeInfo {
    int width = 0, height = 0, slices = 0;  // x fastest, then y, then slice
    double originMm[3] = {0, 0, 0};         // centre of voxel (0, 0, 0)
    double spacingMm[3] = {1, 1, 1};        // z: mean slice spacing (uneven stacks: see JSON)
    std::string description;
};

/// Writes `values` (width·height·slices floats) to `rawPath` and a header
/// `nhdrPath` naming it (relative to the header's folder). Both atomic.
void writeRawVolume(const std::string& nhdrPath, const std::string& rawPath,
                    const std::vector<float>& values, const RawVolumeInfo& info);
void writeRawVolume(const std::string& nhdrPath, const std::string& rawPath,
                    const std::vector<std::uint32_t>& values, const RawVolumeInfo& info);

}  // namespace dfrecon
