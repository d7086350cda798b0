#pragma once
// Sampled volumes as raw little-endian arrays with a detached NRRD header
// (.nhdr), which 3D Slicer, ParaView and ITK/SimpleITK open directly, placed
// in patient LPS space.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/Vec3.hpp"

namespace dfrecon {

struct RawVolumeInfo {
    int width = 0, height = 0, slices = 0;  // x fastest, then y, then slice
    Vec3 originMm;                          // LPS centre of sample (0, 0, 0)
    /// LPS displacement from one sample to the next along each axis (any
    /// orientation: sagittal, coronal and oblique stacks keep their own).
    std::array<Vec3, 3> stepMm{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    /// Empty for evenly spaced slices (one 3D header, stepMm[2] between
    /// slices). Otherwise one LPS origin per slice: no single step places
    /// uneven planes, so each slice gets its own 2D header instead.
    std::vector<Vec3> sliceOriginsMm;
    std::string description;
};

/// Writes `values` (width·height·slices samples) to `rawPath` and headers
/// naming it (relative to the header's folder): `nhdrPath` (3D) for evenly
/// spaced slices, else STEM-NNN.nhdr per slice (STEM = nhdrPath without
/// .nhdr, NNN the slice index from 000), each a 2D image in 3D space at its
/// slice's origin reading its part of the raw file (`byte skip`). Returns
/// the headers written. All atomic. Throws std::invalid_argument when the
/// sizes disagree, std::runtime_error when a file cannot be written. O(values).
std::vector<std::string> writeRawVolume(const std::string& nhdrPath, const std::string& rawPath,
                                        const std::vector<float>& values,
                                        const RawVolumeInfo& info);
std::vector<std::string> writeRawVolume(const std::string& nhdrPath, const std::string& rawPath,
                                        const std::vector<std::uint32_t>& values,
                                        const RawVolumeInfo& info);

}  // namespace dfrecon
