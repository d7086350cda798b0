#pragma once
// The tangents in z of smooth mode's C1 interpolation between planes, shared
// by what it interpolates: each plane's field (recon/SliceInterpolant) and
// the planes' section areas (recon/SlabVolumes), and the slope at an end
// plane that the caps' rims follow (recon/Caps). A tangent is a slope per mm
// of z from the secants of the slabs around a plane.
#include <algorithm>
#include <cmath>
#include <optional>

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

/// Inside the stack, the tangent both interpolants use: the parabola's
/// weighted mean of the secants below and above (dBelow over a slab hBelow
/// high, dAbove over hAbove), each weighed down further by how far it can be
/// trusted (`trustBelow`, `trustAbove` in (0, 1]; 1 and 1: parabolaTangent
/// exactly), or 0 where the value has not changed over the two slabs on one
/// side (a straight stretch: a stem below a branching, a cylinder that
/// starts to narrow), so the surface leaves the plane straight instead of
/// bending the stretch's last slab toward the change on the other side. One
/// flat slab alone is no straight stretch (a bulge symmetric about a slab's
/// middle has one too): the next one decides, read only then —
/// `secantBeyondBelow()` and `secantBeyondAbove()` give the secant of the
/// slab beyond each, or nothing where the stack ends. O(1).
template <class BeyondBelow, class BeyondAbove>
double innerTangent(double hBelow, double dBelow, double hAbove, double dAbove,
                    BeyondBelow&& secantBeyondBelow, BeyondAbove&& secantBeyondAbove,
                    double trustBelow = 1, double trustAbove = 1) {
    if (flatBeside(dBelow, dAbove)) {
        const std::optional<double> beyond = secantBeyondBelow();
        if (beyond && flatBeside(*beyond, dAbove)) return 0;
    }
    if (flatBeside(dAbove, dBelow)) {
        const std::optional<double> beyond = secantBeyondAbove();
        if (beyond && flatBeside(*beyond, dBelow)) return 0;
    }
    return parabolaTangent(hBelow * trustAbove, dBelow, hAbove * trustBelow, dAbove);
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
