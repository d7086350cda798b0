#include "simplify/Simplification.hpp"

#include <chrono>
#include <stdexcept>

#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>

#include "geometry/MeshCheck.hpp"
#include "simplify/CheckedDecimater.hpp"
#include "simplify/InitialPriorities.hpp"
#include "simplify/ModErrorBound.hpp"

namespace dfrecon {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct Attempt {
    TriangleSoup surface;
    ModErrorBound::Bounds bounds;
    std::size_t collapses = 0, cpuEvaluations = 0, batchEvaluations = 0, pieces = 0;
    std::size_t staleCollapses = 0;
    double initialSeconds = 0, decimateSeconds = 0;
};

Attempt decimate(ocl::Runtime* runtime, const TriangleSoup& input, const DeviationSurface& original,
                 const SimplifyOptions& options, const std::vector<bool>& locked) {
    Attempt attempt;
    TriMesh mesh = toTriMesh(input);
    mesh.request_face_normals();
    mesh.update_face_normals();
    for (auto v : mesh.vertices())
        if (locked[std::size_t(v.idx())]) mesh.status(v).set_locked(true);

    CheckedDecimater decimater(mesh);
    ModErrorBound::Handle bound;
    OpenMesh::Decimater::ModNormalFlippingT<TriMesh>::Handle flips;
    decimater.add(bound);
    decimater.add(flips);
    decimater.module(flips).set_max_normal_deviation(options.maxNormalTurnDeg);
    ModErrorBound& module = decimater.module(bound);
    module.setOriginal(original, options.maxErrorMm);
    // Tighter and dearer: the first piece of each created triangle (its
    // centroid distance, or its bound when it settles at once), then the
    // whole deviation; each stops at the first value above the queue's next
    // entry. Stages between them (8 and 64 pieces) only cost their pieces
    // again in the next stage once they stop at the next entry too: without
    // them the bench runs 10-25 % faster. The first asks the flip test before
    // anything else: like the bounds it depends only on the from-vertex's
    // faces, and a collapse it refuses would otherwise cost its lower bounds
    // until judged illegal (on meshes reconstructed from 2 mm planes, a
    // third of the decimation's time).
    auto& flipTest = decimater.module(flips);
    decimater.setLowerBounds({[&module, &flipTest](const auto& ci, float next) {
                                  if (flipTest.collapse_priority(ci) < 0)
                                      return float(ModErrorBound::ILLEGAL_COLLAPSE);
                                  return module.deviationLowerBound(ci, 1, next);
                              },
                              [&module](const auto& ci, float next) {
                                  return module.deviationLowerBound(ci, SIZE_MAX, next);
                              }});

    auto start = std::chrono::steady_clock::now();
    // The batch skips the collapses the flip test refuses: they are dropped
    // at their first lower bound (above), so their values would never be
    // read.
    std::vector<bool> wanted(mesh.n_halfedges());
    for (auto h : mesh.halfedges())
        wanted[std::size_t(h.idx())] =
            flipTest.collapse_priority(ModErrorBound::CollapseInfo(mesh, h)) >= 0;
    module.setInitialDeviations(
        runtime && options.initialBatchOnDevice
            ? initialPriorities(*runtime, mesh, original, options.maxErrorMm, &wanted)
            : initialPrioritiesReference(mesh, original, options.maxErrorMm, &wanted));
    attempt.initialSeconds = secondsSince(start);

    start = std::chrono::steady_clock::now();
    if (!decimater.initialize()) throw std::logic_error("simplify: Decimater refused its modules");
    attempt.collapses = decimater.decimate();
    attempt.staleCollapses = decimater.staleCollapses;
    attempt.bounds = module.currentBounds();
    attempt.cpuEvaluations = module.cpuEvaluations;
    attempt.batchEvaluations = module.initialEvaluations;
    attempt.pieces = module.pieces;
    mesh.garbage_collection();
    attempt.decimateSeconds = secondsSince(start);
    attempt.surface = toTriangleSoup(mesh);
    return attempt;
}

}  // namespace

Simplified simplifySurface(ocl::Runtime* runtime, const TriangleSoup& input,
                           const SimplifyOptions& options) {
    if (!(options.maxErrorMm >= kMinMaxErrorMm))
        throw std::invalid_argument("--max-error must be at least 1e-6 mm");
    std::size_t refused = 0;
    toTriMesh(input, &refused);
    if (refused > 0)
        throw std::invalid_argument("simplify: the surface is not manifold (" +
                                    std::to_string(refused) + " faces refused)");
    const DeviationSurface original(input);
    std::vector<bool> locked(input.points.size(), false);
    Simplified result;
    result.stats.verticesBefore = input.points.size();
    result.stats.trianglesBefore = input.triangles.size();
    // Every collapse is checked when taken, so neither a collision nor a
    // piece of the input out of reach should survive; should one anyway
    // (rounding at the edge of a test), the run is repeated with the input's
    // vertices locked around it — never seen on the tests or benchmarks.
    constexpr int kMaxRetries = 3;
    for (int run = 0;; ++run) {
        Attempt attempt = decimate(runtime, input, original, options, locked);
        const auto pairs = selfIntersectingPairs(attempt.surface);
        SimplifyStats& s = result.stats;
        s.initialSeconds += attempt.initialSeconds;
        s.decimateSeconds += attempt.decimateSeconds;
        const bool withinBound = attempt.bounds.surfaceToOriginalMm <= options.maxErrorMm &&
                                 attempt.bounds.originalToSurfaceMm <= options.maxErrorMm;
        if ((pairs.empty() && withinBound) || run == kMaxRetries) {
            result.surface = std::move(attempt.surface);
            s.vertices = result.surface.points.size();
            s.triangles = result.surface.triangles.size();
            s.collapses = attempt.collapses;
            s.surfaceToInputBoundMm = attempt.bounds.surfaceToOriginalMm;
            s.inputToSurfaceBoundMm = attempt.bounds.originalToSurfaceMm;
            s.cpuEvaluations = attempt.cpuEvaluations;
            s.batchEvaluations = attempt.batchEvaluations;
            s.pieces = attempt.pieces;
            s.staleCollapses = attempt.staleCollapses;
            s.retries = std::size_t(run);
            return result;
        }
        Box3 region;
        for (const auto& [i, j] : pairs)
            for (std::size_t t : {i, j})
                for (std::uint32_t v : attempt.surface.triangles[t])
                    region.add(attempt.surface.points[v]);
        for (const Vec3& p : attempt.bounds.outOfBound) region.add(p);
        const double margin = 4 * options.maxErrorMm;
        region.lo = region.lo - Vec3{margin, margin, margin};
        region.hi = region.hi + Vec3{margin, margin, margin};
        for (std::size_t v = 0; v < input.points.size(); ++v)
            if (region.distance2(input.points[v]) == 0) locked[v] = true;
    }
}

}  // namespace dfrecon
