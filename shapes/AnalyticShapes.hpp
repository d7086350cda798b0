#pragma once
// Analytic solids with exact volume and exact signed distance: the ground
// truth for every test and benchmark. Each shape also yields its planar
// cross-sections as polygons whose vertices lie exactly on the surface.
#include <memory>
#include <string>
#include <vector>

#include "contours/ContourSet.hpp"
#include "geometry/Vec3.hpp"

namespace dfrecon {

/// A point on a shape's surface with its outward unit normal.
struct SurfacePoint {
    Vec3 point, normal;
};

class AnalyticShape {
  public:
    virtual ~AnalyticShape() = default;
    virtual std::string name() const = 0;
    /// Exact enclosed volume in mm³.
    virtual double volumeMm3() const = 0;
    /// Exact Euclidean signed distance to the surface in mm, negative inside.
    virtual double signedDistance(Vec3 p) const = 0;
    /// The z range the solid occupies.
    virtual double zMinMm() const = 0;
    virtual double zMaxMm() const = 0;
    /// The cross-section at plane z as closed polygons (any orientation),
    /// each with about `pointsPerContour` vertices on the exact section curve.
    /// Empty outside (zMin, zMax).
    virtual std::vector<Polygon> section(double zMm, int pointsPerContour) const = 0;
    /// Whether signedDistance is the exact Euclidean distance. Where it is
    /// not (a smooth union), it is still 1-Lipschitz with the surface as its
    /// zero set and the right sign, so |signedDistance| <= the true distance;
    /// measure distances with shapes/SurfaceReference then.
    virtual bool distanceIsExact() const { return true; }
    /// Points on the surface about `stepMm` apart with outward normals, from
    /// the shape's own parametrisation rather than from signedDistance: an
    /// independent reference for tests. Empty for shapes that have none.
    virtual std::vector<SurfacePoint> parametricSurface(double /*stepMm*/) const { return {}; }
};

/// About `count` points on the shape's surface (|signedDistance| < 1e-9 mm),
/// spread over all of it: uniform random points of the bounding box, grown
/// by 10 %, projected along the numerical gradient of the distance. For
/// measuring distances from the surface to a reconstruction.
std::vector<Vec3> sampleSurface(const AnalyticShape& shape, std::size_t count, unsigned seed = 1);

/// The shapes with closed-form sections: sphere, ellipsoid, torus, capsule,
/// y, two-blobs, hollow-sphere (what the reconstruction and simplification
/// tests sweep).
const std::vector<std::string>& shapeNames();

/// Every name makeShape accepts, for synth and the recon benchmark:
/// shapeNames(), then the between-planes family (shapes/BetweenPlanesShapes:
/// bent-tube, torus-30, torus-60, cylinder-30, cylinder-60, plate-20,
/// thin-ellipsoid, neck, branch).
const std::vector<std::string>& allShapeNames();

/// One-line description of a shape's geometry at scale 1 (for --help).
std::string shapeDescription(const std::string& name);

/// The named shape, every length multiplied by `scale`; throws
/// std::invalid_argument for unknown names.
std::unique_ptr<AnalyticShape> makeShape(const std::string& name, double scale = 1.0);

struct SynthOptions {
    double spacingMm = 2.0;     // distance between slices
    int pointsPerContour = 64;  // vertices per full contour
    double noiseMm = 0.0;       // std-dev of random vertex displacement
    unsigned seed = 1;          // random seed for the noise
};

/// Slices `shape` at z = zMin + spacing·(k + ½), k = 0, 1, ... (cell centres,
/// so Σ area·spacing converges to the volume), as one ROI named after the
/// shape, with contours oriented by nesting. Throws std::invalid_argument for
/// bad options, and when noise makes a contour self-intersecting.
ContourSet sliceShape(const AnalyticShape& shape, const SynthOptions& options);

}  // namespace dfrecon
