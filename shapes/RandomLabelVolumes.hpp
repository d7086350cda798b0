#pragma once
// Random structure sets as segmentation tools make them: label volumes of
// blobs, bending tubes and shells with islands in their cavities, at coarse
// voxels, for contoursFromLabels to turn into contours (what a label-to-
// RTSTRUCT converter does). Their contours share pixel edges and corners
// between planes, touch within planes, branch 1→N→1 and nest three deep:
// the coincidences reconstruction must survive. Deterministic per seed.
#include <cstdint>

#include "io/labels/LabelVolume.hpp"

namespace dfrecon {

/// Labels 1 (two to four blobs that overlap, touch or stand apart), 2 (a
/// tube bending through the planes) and 3 (a shell with an island in its
/// cavity) in a 30×30×(8–15) volume with random spacing (0.7–1.3 mm in plane,
/// 1–4 mm between planes); later shapes do not overwrite earlier ones.
/// O(voxels).
LabelVolume hostileLabelVolume(std::uint32_t seed);

/// One label (1) made of `blobs` small random ellipsoids in a volume of
/// `side`×`side`×`planes` voxels of 0.5 mm × 0.5 mm × 2 mm: a structure with
/// many contours per plane, as a CT bone or vessel structure has. O(voxels ×
/// blobs).
LabelVolume manyBlobLabelVolume(std::uint32_t seed, int blobs, int side, int planes);

}  // namespace dfrecon
