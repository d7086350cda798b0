#pragma once
// Signed distance volumes as OpenVDB level sets (.vdb), the format Blender,
// Houdini and OpenVDB pipelines read.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "geometry/PlaneFrame.hpp"
#include "geometry/Vec3.hpp"
#include "geometry/VolumeGrid.hpp"

namespace dfrecon {

struct LevelSetWriteOptions {
    std::string gridName = "surface";
    double bandVoxels = 3;  // narrow band half-width, in voxels of the largest side
    std::map<std::string, std::string> metadata;  // written as string metadata
    /// The volume's axes in patient space: a non-identity frame (sagittal,
    /// coronal, oblique contour stacks) makes the transform an affine map.
    PlaneFrame frame;
};

/// Writes `volume` as a FloatGrid of class level set with a scale-and-
/// translate transform (the voxel sizes may differ per axis): only voxels
/// within the band are stored, the rest is filled by sign (outside
/// +band, inside -band), in world units (mm). Atomic (temporary file and
/// rename). Throws std::invalid_argument for an inconsistent volume,
/// std::runtime_error when the file cannot be written. O(voxels).
void writeLevelSetVdb(const DenseDistanceVolume& volume, const std::string& path,
                      const LevelSetWriteOptions& options);

/// A float grid read back from a .vdb file, sampled in world millimetres
/// (trilinear interpolation of the stored voxels; the background outside
/// the narrow band).
class LevelSetSampler {
  public:
    /// Reads the grid named `gridName`, or the file's first float grid when
    /// empty. Throws InputError naming the file when it cannot be read, or
    /// holds no such grid.
    explicit LevelSetSampler(const std::string& path, const std::string& gridName = {});
    ~LevelSetSampler();
    LevelSetSampler(LevelSetSampler&&) noexcept;

    const std::string& gridName() const;
    /// The interpolated value at p. Thread-safe. O(1).
    double operator()(Vec3 p) const;

  private:
    struct Grid;
    std::unique_ptr<Grid> grid_;
};

}  // namespace dfrecon
