#pragma once
// Label volumes → contour slices: the borders of each label on every plane of
// the volume's third axis, at the half-way level between inside and outside
// voxel centres (the contours an RT Structure Set would hold for a
// segmentation).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "contours/ContourSet.hpp"
#include "io/labels/LabelVolume.hpp"

namespace dfrecon {

struct MaskContourOptions {
    /// ROI names by label; labels not listed are named "label_N".
    std::map<std::int32_t, std::string> names;
    /// ROI display colours by label; labels not listed get none.
    std::map<std::int32_t, Rgb> colours;
    /// The label that is no structure (no ROI is made for it).
    std::int32_t backgroundLabel = 0;
    /// When not empty: the position along the frame's normal of each plane
    /// k, one per plane, strictly increasing (a mask stack with uneven
    /// slice positions); replaces originMm and spacingMm[2] for z.
    std::vector<double> planePositionsMm;
    /// Names the input in InputError messages.
    std::string sourceName = "label volume";
};

/// One ROI per label other than the background present in `volume`, in
/// increasing label order, named from options.names or "label_N", with
/// number N. Each plane k of axis 2 that holds the label gives a Slice whose
/// contours are the borders of {label == N} at the level 0.5 between inside
/// (1) and outside (0) voxel centres: every vertex is the midpoint of a
/// lattice edge between an inside and an outside voxel centre, so borders
/// cut the corners of the voxel squares. Inside voxels that touch only
/// diagonally are separate regions. Holes and islands are kept; outer
/// contours run counter-clockwise, holes clockwise (Slice's convention).
///
/// Coordinates: a contour point (x, y) on a slice at z satisfies
/// frame.toPatient(x, y, z) = geometry.worldOfIndex(i, j, k) for its
/// fractional voxel index. When direction[2] is a patient axis the frame is
/// canonicalFrame()'s, so every axial volume (LPS or RAS, slices head or
/// feet first) gives the identity frame: x, y, z are patient LPS. Otherwise
/// u = direction[0], v = direction[1] and n = ±direction[2] (the sign that
/// makes it right-handed); planePositionsMm are along that n. Slices are
/// sorted by increasing z; slabThicknessMm is the slice spacing (each plane
/// stands for a slab of voxels).
///
/// Throws InputError(options.sourceName, 0, ...) when the volume's axes are
/// not orthogonal (|cos| > 1e-4 between two directions; nearly orthogonal
/// axes are orthonormalised), when labels.size() does not match the
/// geometry, or when planePositionsMm has the wrong count or is not strictly
/// increasing. O(voxels + Σ over labels and planes of the label's bounding
/// box area in that plane).
ContourSet contoursFromLabels(const LabelVolume& volume, const MaskContourOptions& options = {});

}  // namespace dfrecon
