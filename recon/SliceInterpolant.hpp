#pragma once
// A C1 implicit function through a stack of slices: F(x, y, z) is each
// slice's signed distance field (bilinear between pixel centres) and, between
// the planes, a cubic Hermite interpolation in z whose tangent at a plane is
// the slope of the parabola through that plane's value and its neighbours'
// (0 where the field is flat over the two slabs on one side: a straight
// stretch stays straight; the end slab's secant at the first and last
// plane: recon/HermiteTangents). A neighbour's secant counts less where the
// two planes' gradients at the point point apart: there the point lies
// across a medial axis on one of them (the far face of a thin tilted plate,
// one plane away), and the parabola through both faces' distances would
// bend the near face outward.
// It equals each slice's field on its plane, has a continuous z-derivative
// across planes (the tangent is shared by the slabs above and below), and
// reproduces any field quadratic in z whose gradient keeps its direction
// from plane to plane, so a surface that bulges between two
// planes (convex anatomy half-way) bulges in F too, which a monotone
// interpolant cannot do. Its zero set, moved outward in the plane by a
// bulge per slab (or per nested part of a slab, recon/LoftSmoothing), is what
// `--interpolation smooth` bends the loft bands onto.
#include <cstddef>
#include <vector>

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
    /// slab's secant in z continues (a single slice: its field). O(1): four
    /// planes' bilinear look-ups.
    double value(Vec3 p) const;
    /// dF/dx and dF/dy at p by central differences of half a pixel. O(1).
    Point2 gradientXy(Vec3 p) const;

    /// The slab [slice s, s + 1] containing z (the first or last for z
    /// outside the stack).
    std::size_t slabAt(double zMm) const;
    /// The height of that slab, mm (0 for a single slice).
    double slabHeightAt(double zMm) const;
    /// The smaller of the two fields of p's slab's planes at p's xy: <= 0
    /// inside the union of the two planes' regions. O(1): two
    /// planes' bilinear look-ups.
    double neighbourPlanesValue(Vec3 p) const;
    /// Its d/dx and d/dy at p, as gradientXy takes F's. O(1).
    Point2 neighbourPlanesGradientXy(Vec3 p) const;

  private:
    double planeValue(std::size_t slice, Point2 p) const;
    /// A plane's field at p and its gradient there (per pixel, not per mm:
    /// only its direction is read), of the same bilinear cell. O(1).
    struct PlaneSample {
        double value = 0;
        Point2 gradient{0, 0};
    };
    PlaneSample planeSample(std::size_t slice, Point2 p) const;
    /// dF/dz at plane `slice`, from the field there (`here`) and on the
    /// planes below and above it (unused where the stack ends): the slope of
    /// the parabola through the three, its secants weighed by how far each
    /// can be trusted (`trustBelow`, `trustAbove`: less across a medial
    /// axis), or 0 where the field is flat over the two slabs on one side of
    /// the plane (reading the plane beyond, at `xy`, only then).
    double tangent(std::size_t slice, Point2 xy, double below, double here, double above,
                   double trustBelow, double trustAbove) const;

    const SliceFields& fields_;
};

}  // namespace dfrecon
