#pragma once
// A C1 implicit function through a stack of slices: F(x, y, z) is each
// slice's signed distance field (bilinear between pixel centres) and, between
// the planes, a monotone cubic Hermite interpolation in z (Fritsch–Carlson
// tangents). It equals each slice's field on its plane, has a continuous
// z-derivative across planes (the tangent at a plane is shared by the slabs
// above and below), and between two planes never leaves the range of their
// two values, so it does not overshoot where a shape ends or branches. Its
// zero set is what `--interpolation smooth` bends the loft bands onto.
#include <cstddef>

#include "field/SliceFields.hpp"
#include "geometry/Polygon.hpp"
#include "geometry/Vec3.hpp"

namespace dfrecon {

class SliceInterpolant {
  public:
    /// Over `fields` (slices in increasing z, every slice with contours, so
    /// every value finite). Keeps a reference: `fields` must outlive it.
    explicit SliceInterpolant(const SliceFields& fields);

    /// F at p, mm (< 0 inside). Beyond the first and last plane, the end
    /// slab's secant in z continues (a single slice: its field). O(1).
    double value(Vec3 p) const;
    /// dF/dx and dF/dy at p by central differences of half a pixel. O(1).
    Point2 gradientXy(Vec3 p) const;

    /// The slab [slice s, s + 1] containing z (the first or last for z
    /// outside the stack).
    std::size_t slabAt(double zMm) const;
    /// The height of that slab, mm (0 for a single slice).
    double slabHeightAt(double zMm) const;

  private:
    double planeValue(std::size_t slice, Point2 p) const;

    const SliceFields& fields_;
};

}  // namespace dfrecon
