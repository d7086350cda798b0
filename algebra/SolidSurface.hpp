#pragma once
// The boundary of the solid where a field is negative, as a closed
// triangle mesh in space: the exact surface of a margin or a Boolean
// between the planes, not a surface interpolated from its contours.
//
// The field is sampled at voxel centres only near its zero set: space is
// cut into blocks, and a block whose centre lies farther from zero than
// the field can change across it (its Lipschitz constant times half the
// block's diagonal) holds no boundary and is filled with its centre's sign
// as an OpenVDB tile. OpenVDB's mesher (tools::volumeToMesh) then draws the
// zero set, and every vertex is moved onto the exact zero set by a Newton
// step along the field's central-difference gradient, then a secant step.
// Away from creases the surface lies within 1e-3 mm of the exact one; at a
// crease (a shrink's edge, where a difference cuts) the mesher's vertices
// cut it by up to a voxel.
#include <cstddef>
#include <functional>
#include <vector>

#include "geometry/Box3.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

struct SolidSurfaceOptions {
    double voxelMm = 0.5;
    int blockVoxels = 8;
    /// Largest number of voxels sampled; beyond, the voxel grows (and is
    /// reported) until it is not exceeded.
    std::size_t maxSamples = std::size_t(1) << 24;
    /// Move the mesher's vertices onto the exact zero set (false: leave
    /// them where linear interpolation put them, within a voxel).
    bool projectVertices = true;
};

struct SolidSurfaceStats {
    double voxelMm = 0;  // as used
    std::size_t blockSamples = 0, voxelSamples = 0, vertexSamples = 0;
    double largestStepMm = 0;  // the largest move of a vertex onto the zero set
    bool projected = true;     // vertices moved onto the zero set (the caller may undo it)
};

/// A field at points in space: negative inside.
using SpaceField = std::function<std::vector<double>(const std::vector<Vec3>& points)>;

/// The zero set of `field` within `support` (a box holding every point
/// where it is ≤ 0), for a field that changes by at most `lipschitz` per mm
/// in any direction. Outward triangles (not checked: see geometry/
/// MeshCheck). Throws std::invalid_argument for a voxel that is not
/// positive or a Lipschitz constant that is not finite and positive.
/// O(blocks + voxels near the surface + vertices) field evaluations.
TriangleSoup solidSurface(const SpaceField& field, double lipschitz, const Box3& support,
                          const SolidSurfaceOptions& options = {},
                          SolidSurfaceStats* stats = nullptr);

}  // namespace dfrecon
