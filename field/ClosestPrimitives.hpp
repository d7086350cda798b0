#pragma once
// For points on the objects of a scene, the closest primitive — triangle,
// edge or vertex — of the *other* objects (paper §3.1: the surface distance
// map D(q) and the nearest-object map N(q) at sample points q). Three
// implementations of one definition:
//   closestPrimitives          OpenCL (kernels/surface_distance.cl over the
//                              closest_triangle_3d.cl family), the fast one
//   closestPrimitivesReference the same algorithm in C++ (its test oracle)
//   closestPrimitivesBruteForce every triangle of every other object; the
//                              independent reference and the benchmark's
//                              baseline
// The kernel and its reference cull once per source triangle (a triangle
// holding samples): tangent-plane lower bounds (kernels/tangent_bound.cl)
// rule out the subtrees and triangles of the other objects' hierarchies
// that cannot be nearest anywhere on it, and each sample measures only the
// few that remain (docs/surface-distance-maps.md, "The kernel").
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "cl/Runtime.hpp"
#include "field/SurfaceScene.hpp"

namespace dfrecon {

/// A point on object `object`, lying on its triangle `triangle`.
struct SurfaceSample {
    Vec3 point;
    std::uint32_t object = 0;
    std::uint32_t triangle = 0;
};

struct DistanceQuery {
    /// -1: every other object; else only this object (pairwise maps).
    int target = -1;
    /// Primitives farther than this are not looked for (a clearance band:
    /// answers beyond it come back with object -1).
    double maxDistanceMm = std::numeric_limits<double>::infinity();
};

struct ClosestPrimitive {
    /// Distance to the closest point; negative when the sample is inside
    /// that object (closed objects only). +inf when none within the band.
    double distanceMm = std::numeric_limits<double>::infinity();
    std::int32_t object = -1;    // -1: none within the band
    std::uint32_t triangle = 0;  // in that object
    TriangleFeature feature = TriangleFeature::Face;
    Vec3 point;  // the closest point
};

/// What the culling of a run() did: source triangles (those holding
/// samples), how many of them overflowed their list (their samples searched
/// the hierarchies), and the candidates the others listed in all.
struct CullStats {
    std::size_t sources = 0, overflowing = 0, candidates = 0;
};

/// C++ reference: the kernel's steps in C++ (candidates per source triangle,
/// then per sample). O(F log T + S·c) typically, F source triangles, c
/// candidates each (about 10).
std::vector<ClosestPrimitive> closestPrimitivesReference(const SurfaceScene& scene,
                                                         const std::vector<SurfaceSample>& samples,
                                                         const DistanceQuery& query = {});

/// For points anywhere (a grid, the planes of a margin), on no object: the
/// closest primitive of every object, or of query.target alone, signed
/// (negative inside a closed object), by a search of the hierarchies.
/// The exact Euclidean distance to the nearest surface, up to rounding.
/// O(P log T) typically.
std::vector<ClosestPrimitive> closestPrimitivesAtReference(const SurfaceScene& scene,
                                                           const std::vector<Vec3>& points,
                                                           const DistanceQuery& query = {});

/// Every triangle of every candidate object for every sample (a sample of
/// object UINT32_MAX lies on none, so every object is a candidate). O(S·T).
std::vector<ClosestPrimitive> closestPrimitivesBruteForce(const SurfaceScene& scene,
                                                          const std::vector<SurfaceSample>& samples,
                                                          const DistanceQuery& query = {});

/// The scene's triangles and hierarchies on a device, uploaded once, for any
/// number of queries (e.g. one per object's atlas, or per frame).
class ClosestPrimitiveKernel {
  public:
    /// `sourcesPerLaunch` bounds how many sampled triangles get their
    /// candidate lists at once (0: the default, 16 384, about 38 MB); the
    /// answers do not depend on it.
    ClosestPrimitiveKernel(ocl::Runtime& runtime, const SurfaceScene& scene,
                           std::size_t sourcesPerLaunch = 0);
    ~ClosestPrimitiveKernel();
    ClosestPrimitiveKernel(const ClosestPrimitiveKernel&) = delete;
    ClosestPrimitiveKernel& operator=(const ClosestPrimitiveKernel&) = delete;

    /// The same answers as closestPrimitivesReference: distances agree to
    /// rounding in double precision (PoCL) and within 1e-6 of the scene's
    /// extent in single precision; at ties (points equally near two
    /// primitives) the primitive may differ. Two launches: one per source
    /// triangle (its candidates), one per sample.
    std::vector<ClosestPrimitive> run(const std::vector<SurfaceSample>& samples,
                                      const DistanceQuery& query = {});

    /// Points anywhere: the same answers as closestPrimitivesAtReference,
    /// with run()'s tolerance. One launch per 262 144 points. Does not
    /// change lastCullStats().
    std::vector<ClosestPrimitive> runAt(const std::vector<Vec3>& points,
                                        const DistanceQuery& query = {});

    /// The culling of the last run() (benchmarks report it).
    CullStats lastCullStats() const;

    /// Relative tolerance of run() against the reference, times the scene's
    /// extent: 0 in double precision up to rounding, 1e-6 in single.
    double toleranceMm() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace dfrecon
