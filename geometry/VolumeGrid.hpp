#pragma once
// Regular voxel grids in patient space, as files and fields share them: the
// grid of a label volume or image series (VolumeGeometry: the DICOM, NRRD
// and ITK convention, positions at voxel centres, any axes), and a dense
// signed distance volume on axis-aligned voxels (DenseDistanceVolume). Plain
// data with their index arithmetic; the files that hold them are io/'s.
#include <array>
#include <cstddef>
#include <vector>

#include "geometry/Vec3.hpp"

namespace dfrecon {

/// A voxel grid in patient space. Voxel (i, j, k) is centred at
/// originMm + i·spacingMm[0]·direction[0] + j·spacingMm[1]·direction[1]
///          + k·spacingMm[2]·direction[2]
/// (the convention of DICOM, NRRD and ITK: positions are voxel centres).
struct VolumeGeometry {
    std::array<int, 3> size{{0, 0, 0}};            // voxels along axes 0 (fastest), 1, 2
    std::array<double, 3> spacingMm{{1, 1, 1}};    // centre-to-centre distance along each axis
    std::array<double, 3> originMm{{0, 0, 0}};     // LPS position of the CENTRE of voxel (0,0,0)
    std::array<std::array<double, 3>, 3> direction{// direction[a]: unit vector of axis a, LPS
                                                   {{{1, 0, 0}}, {{0, 1, 0}}, {{0, 0, 1}}}};

    /// size[0]·size[1]·size[2] (0 when a size is not positive). O(1).
    std::size_t voxelCount() const;
    /// Position in labels of voxel (i, j, k): (k·size[1] + j)·size[0] + i. O(1).
    std::size_t linearIndex(int i, int j, int k) const;
    /// LPS millimetres of index (i, j, k); fractional indices give points
    /// between voxel centres, (-0.5, -0.5, -0.5) is the outer corner of the
    /// first voxel. O(1).
    Vec3 worldOfIndex(double i, double j, double k) const;
    /// The inverse of worldOfIndex: fractional (i, j, k) of an LPS point.
    /// Throws std::domain_error when the axes are degenerate (parallel
    /// directions or zero spacing). O(1).
    std::array<double, 3> indexOfWorld(Vec3 pointMm) const;
};

/// Below this |det| of the unit axis directions the axes are taken as
/// parallel: a voxel's volume would be under a millionth of
/// spacing[0]·spacing[1]·spacing[2], which no scanner writes.
inline constexpr double kMinAxisDeterminant = 1e-6;

/// The determinant of the matrix whose columns are columns[0..2]. O(1).
double axesDeterminant(const std::array<std::array<double, 3>, 3>& columns);

/// A dense signed distance volume in mm (negative inside): voxel (i, j, k)
/// is centred at originMm + (i·voxelMm[0], j·voxelMm[1], k·voxelMm[2]), and
/// its value is valuesMm[(k·ny + j)·nx + i].
struct DenseDistanceVolume {
    int nx = 0, ny = 0, nz = 0;
    double originMm[3] = {0, 0, 0};
    double voxelMm[3] = {1, 1, 1};
    std::vector<float> valuesMm;
};

}  // namespace dfrecon
