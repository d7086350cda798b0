#pragma once
// Smooth solids that stress what happens between contour planes (issue 17):
// tubes bending through the planes, tori and cylinders lying at an angle,
// plates thinner than the spacing, a neck and a branch. Each lies obliquely
// to the planes, so its sections shift, turn, split and vanish between them.
//
// Every shape but `branch` has an exact signed distance (a rigid placement
// of an exact local distance); `branch` is a smooth union of capsules whose
// distance is a bound (AnalyticShape::distanceIsExact). Sections are traced
// from the distance (shapes/ImplicitSection), every vertex on the surface.
#include <memory>
#include <string>
#include <vector>

#include "shapes/AnalyticShapes.hpp"

namespace dfrecon {

/// bent-tube, torus-30, torus-60, cylinder-30, cylinder-60, plate-20,
/// thin-ellipsoid, neck, branch.
const std::vector<std::string>& betweenPlanesShapeNames();

/// One-line description at scale 1, or "" for a name not of this family.
std::string betweenPlanesShapeDescription(const std::string& name);

/// The named shape with every length times `scale`; nullptr for a name not of
/// this family.
std::unique_ptr<AnalyticShape> makeBetweenPlanesShape(const std::string& name, double scale);

}  // namespace dfrecon
