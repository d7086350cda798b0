#pragma once
// The fixed limits every reader holds its input to, so that a hostile or
// broken file is refused as bad input (exit 2, the file named) before it can
// exhaust time, memory or the stack. docs/cli.md ("Limits on input") lists
// them for users, with the limits that belong to one format.
#include <cstddef>
#include <cstdint>

namespace dfrecon {

/// Largest |coordinate| of any point read (mesh vertices, contour points,
/// label-volume voxel centres and corners): a kilometre. Patient and
/// scanner coordinates are within a few metres; beyond this, sums of
/// squares and grids lose their precision or overflow.
inline constexpr double kMaxAbsCoordinateMm = 1e6;

/// Smallest voxel spacing a label volume or mask stack may have: a
/// nanometre. Below it distinct planes would coincide within rounding.
inline constexpr double kMinVoxelSpacingMm = 1e-6;

/// Most corners of one polygon face of a mesh file. OpenMesh's importer
/// compares every corner of a face with every other (quadratic), and no
/// mesh face has more.
inline constexpr std::size_t kMaxMeshFaceCorners = 4096;

/// Most triangles at one vertex of a mesh file. The self-intersection check
/// compares every pair of triangles whose boxes overlap, and all of a fan's
/// do: 10^5 triangles at a vertex never ended, 10^4 take a few seconds. No
/// surface this program reads or writes comes near (a sphere's pole in a
/// fine UV mesh has a few hundred).
inline constexpr std::size_t kMaxTrianglesAtVertex = 10000;

/// Memory budget of a label volume: the decoded samples plus the 32-bit
/// label per voxel must fit in 2 GiB, checked from the header before
/// anything is allocated (a small gzip file can claim billions of voxels).
inline constexpr std::uint64_t kMaxLabelVolumeBytes = std::uint64_t(2) << 30;

/// Deepest nesting of DICOM sequences accepted (an RT Structure Set nests
/// three deep; DCMTK's parser recurses once per level and exhausts the
/// stack on tens of thousands).
inline constexpr std::size_t kMaxDicomNestingDepth = 64;

/// Most contours plus crossing points in one group of contours of a plane
/// combined by exclusive or (CLOSEDPLANAR_XOR, shared edges). CGAL's exact
/// arrangement takes about 2 kB and 0.1 ms per crossing; 50 000 take some
/// 5 s and 200 MB. Real planes have a handful.
inline constexpr std::size_t kMaxXorCrossingsPerPlane = 50000;
/// The same for all planes of a file together (some 15 s at most).
inline constexpr std::size_t kMaxXorCrossingsPerFile = 150000;

}  // namespace dfrecon
