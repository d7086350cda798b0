#pragma once
// The tangents in z of smooth mode's C1 interpolation between planes, shared
// by what it interpolates: each plane's field (recon/SliceInterpolant) and
// the planes' section areas (recon/SlabVolumes), and the slope at an end
// plane that the caps' rims follow (recon/Caps). A tangent is a slope per mm
// of z from the secants of the slabs around a plane.
#include <algorithm>
#include <cmath>

namespace dfrecon {

/// A secant at most this fraction of the one on the plane's other side
/// counts as flat (the value did not change over that slab): exactly flat
/// on identical planes, with room for the fields' float rounding.
inline constexpr double kFlatSecantRatio = 0.05;

/// Is `secant` flat beside `other`, the secant across the plane? O(1).
inline bool flatBeside(double secant, double other) {
    return std::fabs(secant) <= kFlatSecantRatio * std::fabs(other);
}

/// Inside the stack: the slope of the parabola through a plane and its two
/// neighbours, from the secants below and above over slabs hBelow and
/// hAbove high: a weighted mean of the two, never steeper than the steeper,
/// exact for a quadratic in z. O(1).
inline double parabolaTangent(double hBelow, double secantBelow, double hAbove,
                              double secantAbove) {
    return (hAbove * secantBelow + hBelow * secantAbove) / (hBelow + hAbove);
}

/// At an end plane: the slope of the parabola through the end slab's two
/// planes with `innerTangent`, the tangent at the slab's other plane:
/// 2·secant − innerTangent. A rounded end (a ball's pole region, a
/// capsule's tip) leaves its last plane steeper than the end slab's secant,
/// a cone's end as steep as it. Kept on the secant's side of 0 (an end that
/// closes never turns into one that opens) and at most twice as steep: the
/// parabola whose vertex is the inner plane, the widest section the planes
/// saw. Steeper would say the section peaks between the planes, where no
/// plane saw it (three times, the monotone-cubic bound, shrank lens-like
/// areas of three planes). The caps' rims follow it; the field and the
/// areas keep the end slab's secant at the end planes
/// (docs/reconstruction.md, "Caps that follow a rounded end", says what
/// using it there did). O(1).
inline double endTangent(double secant, double innerTangent) {
    const double m = 2 * secant - innerTangent;
    if (m * secant <= 0) return 0;
    return std::fabs(m) > 2 * std::fabs(secant) ? 2 * secant : m;
}

}  // namespace dfrecon
