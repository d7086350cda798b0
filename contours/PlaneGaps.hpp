#pragma once
// Planes left empty inside an ROI. Planning systems draw structures on the
// planes of an image series; a structure with no contour on planes between
// planes where it has contours ends there and starts again (a gap left on
// purpose, or a structure in two pieces), and their volume, Σ area ×
// thickness, counts nothing for those planes. dfrecon reads such an ROI the
// same way in the surface (each run of planes its own closed piece, capped
// like any end), the contour volume and the label map (docs/formats.md,
// "Planes left empty inside an ROI").
#include <vector>

#include "contours/ContourSet.hpp"

namespace dfrecon {

/// Finds, for every ROI of `set`, where it ends and starts again, and the
/// spacing of the image planes it was drawn on, filling Roi::restartsAt and
/// Roi::imagePlaneSpacingMm. The image planes are those of every ROI of the
/// set on the same stack (the same plane normal, either way round; planes
/// within 0.01 mm are one). Between two neighbouring planes of an ROI the
/// ROI restarts when an image plane lies between them and their gap is
/// more than 1.5 times the ROI's own smallest gap (ROIs of three planes or
/// more) or the image planes' spacing (the median gap between image
/// planes): so an ROI drawn on every other plane of its own, or on a series
/// whose planes interleave another's, is not cut. O(P log P) for P planes
/// in all.
void findPlaneGaps(ContourSet& set);

/// The runs of planes of `roi` (Roi::restartsAt), each as an ROI of its own
/// with the same name, frame and thicknesses; a lone plane of a run keeps
/// roi's imagePlaneSpacingMm. One run (a copy of `roi`) when it never
/// restarts. O(points).
std::vector<Roi> planeRuns(const Roi& roi);

/// The thickness a plane with no neighbour in its run stands for: the slab
/// thickness when given, else the image planes' spacing when known, else 0.
/// O(1).
double lonePlaneThicknessMm(const Roi& roi);

/// How thick a surface stands on an ROI's one plane when nothing says
/// (lonePlaneThicknessMm 0): its contour volume then counts 0, and reading
/// warns of it.
inline constexpr double kUnknownLonePlaneThicknessMm = 1.0;

}  // namespace dfrecon
