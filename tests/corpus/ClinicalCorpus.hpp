#pragma once
// Generators of planning-system structure sets: what clinical exports hold
// and atlases do not. Each case is a whole set (a body outline on every
// plane, so that the image planes are known, and the structures of its
// kind), drawn the way planning systems draw: a lung outline with dozens of
// 4- to 8-point vessels that appear and vanish from plane to plane,
// outlines that cross themselves, fold back and repeat points, contours
// stored twice, 1 mm SRS slabs, oblique planes, neighbours that share their
// border, and ROIs with planes left empty. A seed picks every size, spacing
// and position; the same seed gives the same set.
#include <cstdint>
#include <string>
#include <vector>

#include "contours/ContourSet.hpp"

namespace dfrecon::testing {

enum class CorpusKind {
    VesselHoles,         // a lung with small holes appearing and vanishing
    CrossingOutlines,    // self-crossing loops, folds, repeated points, loops over the start
    StoredTwice,         // every contour stored twice (some reversed, some rotated)
    SrsSlabs,            // small targets on 1 mm planes, some a single plane
    ObliquePlanes,       // contours on a tilted stack
    TouchingNeighbours,  // two structures sharing their border; lobes touching at a point
    PlanesLeftEmpty,     // planes with no contour between planes with contours
};

inline const std::vector<std::pair<CorpusKind, const char*>> kCorpusKinds{
    {CorpusKind::VesselHoles, "VesselHoles"},
    {CorpusKind::CrossingOutlines, "CrossingOutlines"},
    {CorpusKind::StoredTwice, "StoredTwice"},
    {CorpusKind::SrsSlabs, "SrsSlabs"},
    {CorpusKind::ObliquePlanes, "ObliquePlanes"},
    {CorpusKind::TouchingNeighbours, "TouchingNeighbours"},
    {CorpusKind::PlanesLeftEmpty, "PlanesLeftEmpty"},
};

/// The structure set of `kind` for `seed`, as a planning system would export
/// it: the contours exactly as drawn (crossing, folded, twice), not yet read.
/// Every ROI's frame and plane positions are set; contour points are in the
/// ROI's plane frame. O(points).
ContourSet clinicalCase(CorpusKind kind, std::uint32_t seed);

}  // namespace dfrecon::testing
