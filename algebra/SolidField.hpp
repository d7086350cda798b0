#pragma once
// The field of a structure expression: at any point, a value that is
// negative exactly inside the expression's solid, built from the exact
// signed distances to the ROIs' closed surfaces (field/ClosestPrimitives,
// the closest-primitive kernel at free points). A margin of an ROI is a
// level of its distance (an ellipsoidal margin a level of the distance in
// space scaled by the ellipsoid's axes); union is the minimum, intersection
// the maximum, difference max(a, −b), exclusive or min(max(a, −b),
// max(b, −a)). Every leaf is divided by its Lipschitz constant within the
// planes of the output, so the whole field changes by at most the distance
// moved in a plane: algebra/PlaneSections relies on that to skip cells.
#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "algebra/RoiExpression.hpp"
#include "cl/Runtime.hpp"
#include "geometry/Box3.hpp"
#include "geometry/PlaneFrame.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

/// Smallest semi-axis an ellipsoidal margin is given: a margin of 0 along
/// one axis (grow in the plane only) is an ellipsoid this flat, not a disc.
inline constexpr double kFlatMarginAxisMm = 1e-3;

/// Where the field's distances come from.
enum class DistanceBackend {
    Device,    // ClosestPrimitiveKernel::runAt on the runtime's device
    Reference  // closestPrimitivesAtReference, its C++ twin
};

class ExpressionField {
  public:
    /// `lowered`: an expression after marginsOnRois (margins only on ROIs).
    /// `surfaces`: each ROI's closed, outward surface in patient mm, by
    /// name. `planes`: the frame of the planes the field will be asked on
    /// (its Lipschitz bound is taken within them). `runtime` may be null
    /// with DistanceBackend::Reference. A margin that differs between the
    /// two senses of an axis (R ≠ L, A ≠ P or S ≠ I) is the body of eight
    /// ellipsoid octants (algebra/OctantGauge), its gauge found on the host
    /// near the surface. Throws std::invalid_argument for an ROI without a
    /// surface or a surface that is not closed. O(T log T) in all the
    /// triangles, once per margin shape.
    ExpressionField(const RoiExpression& lowered,
                    const std::map<std::string, TriangleSoup>& surfaces, const PlaneFrame& planes,
                    DistanceBackend backend, ocl::Runtime* runtime);
    ~ExpressionField();
    ExpressionField(const ExpressionField&) = delete;
    ExpressionField& operator=(const ExpressionField&) = delete;

    /// The field at points in patient mm: negative exactly inside the
    /// expression's solid (up to the distances' rounding), 1-Lipschitz along
    /// the planes. One distance query per point and ROI and margin shape
    /// (ROIs' distances shared between leaves with the same shape).
    std::vector<double> values(const std::vector<Vec3>& patientPoints);

    /// A box (patient mm) holding every point where the field is ≤ 0; empty
    /// (lo > hi) when the expression is empty for sure (disjoint boxes of an
    /// intersection).
    Box3 support() const;

    /// A bound on how fast the field changes per mm in any direction (1
    /// without ellipsoidal margins; an ellipsoid with a flat axis makes it
    /// large). O(leaves).
    double lipschitzInSpace() const;

    /// How far the values may be off by rounding (mm): the distances'
    /// tolerance (ClosestPrimitiveKernel::toleranceMm, 1e-12 of the scene's
    /// extent in double precision, 1e-6 in single) over the smallest norm,
    /// and never below 1e-9. O(shapes).
    double toleranceMm() const;

    /// Whether a leaf is an eight-octant margin (its values come from the
    /// host, about a hundred times slower than distances). O(leaves).
    bool hasOctantMargins() const;

    /// Points evaluated so far (each point once per distance query).
    std::size_t distanceQueries() const { return queries_; }

  private:
    struct Leaf;
    struct Shape;
    /// An eight-octant margin's values at `points` from their distances.
    void octantValues(const Leaf& leaf, const std::vector<double>& distance,
                      const std::vector<Vec3>& points, std::vector<double>& out) const;
    const RoiExpression expression_;
    std::vector<std::unique_ptr<Shape>> shapes_;
    std::vector<Leaf> leaves_;  // by node index (leaves only used)
    std::vector<std::size_t> leafOfNode_;
    std::size_t queries_ = 0;
};

}  // namespace dfrecon
