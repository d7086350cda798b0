#include "algebra/DistanceHistograms.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "field/ClosestPrimitives.hpp"
#include "field/Rasterization.hpp"
#include "geometry/SurfaceMeasures.hpp"
#include "geometry/TriangleCells.hpp"

namespace dfrecon {

namespace {

// Sorts samples by distance and sums their weights.
WeightedDistances sorted(const std::vector<double>& distance, const std::vector<double>& weight) {
    std::vector<std::size_t> order(distance.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return distance[a] < distance[b]; });
    WeightedDistances out;
    for (std::size_t k : order) {
        out.distanceMm.push_back(distance[k]);
        out.weight.push_back(weight[k]);
        out.total += weight[k];
        out.cumulative.push_back(out.total);
    }
    return out;
}

// Queries per batch: a progress bar moves between batches, and each
// batch's results stay small.
constexpr std::size_t kQueriesPerBatch = std::size_t(1) << 18;

// Signed distances from points to object `object` of `scene`, in batches;
// `done(k)` after each with the points done so far.
std::vector<double> signedDistances(const SurfaceScene& scene, ClosestPrimitiveKernel* kernel,
                                    std::size_t object, const std::vector<Vec3>& points,
                                    const std::function<void(std::size_t)>& done) {
    DistanceQuery query;
    query.target = int(object);
    std::vector<double> d(points.size());
    for (std::size_t first = 0; first < points.size(); first += kQueriesPerBatch) {
        const std::size_t last = std::min(points.size(), first + kQueriesPerBatch);
        const std::vector<Vec3> batch(points.begin() + std::ptrdiff_t(first),
                                      points.begin() + std::ptrdiff_t(last));
        const std::vector<ClosestPrimitive> found =
            kernel ? kernel->runAt(batch, query)
                   : closestPrimitivesAtReference(scene, batch, query);
        for (std::size_t k = 0; k < batch.size(); ++k) d[first + k] = found[k].distanceMm;
        done(last);
    }
    return d;
}

}  // namespace

double WeightedDistances::fractionWithin(double d) const {
    if (total <= 0) return 0;
    const std::size_t below =
        std::size_t(std::upper_bound(distanceMm.begin(), distanceMm.end(), d) - distanceMm.begin());
    return below == 0 ? 0 : cumulative[below - 1] / total;
}

double WeightedDistances::meanMm() const {
    double sum = 0;
    for (std::size_t k = 0; k < distanceMm.size(); ++k) sum += distanceMm[k] * weight[k];
    return total > 0 ? sum / total : 0;
}

DistanceHistograms distanceHistograms(const TriangleSoup& oar, const TriangleSoup& target,
                                      const DistanceHistogramOptions& options,
                                      ocl::Runtime* runtime) {
    if (!(options.volumeStepMm > 0) || !(options.surfaceSpacingMm > 0))
        throw std::invalid_argument("distanceHistograms: steps must be > 0 mm");
    const SurfaceScene scene({oar, target}, {"OAR", "target"});
    for (std::size_t o = 0; o < 2; ++o)
        if (!scene.closed(o))
            throw std::invalid_argument(std::string("the ") + (o ? "target" : "OAR") +
                                        "'s surface is not closed");
    std::unique_ptr<ClosestPrimitiveKernel> kernel;
    if (options.backend == DistanceBackend::Device) {
        if (!runtime)
            throw std::invalid_argument("distanceHistograms: the device backend needs a runtime");
        kernel = std::make_unique<ClosestPrimitiveKernel>(*runtime, scene);
    }
    DistanceHistograms out;
    const SurfaceMeasures measures = measureSurface(oar);
    out.oarVolumeMm3 = measures.volumeMm3;
    out.oarAreaMm2 = measures.areaMm2;

    // Volume: cell centres of a grid over the OAR's box, kept where inside.
    Box3 box;
    for (const Vec3& p : oar.points) box.add(p);
    const Vec3 size = box.hi - box.lo;
    double step = options.volumeStepMm;
    // Cells tiling the box (the midpoint rule): centres half a step in from
    // its faces, never on them, where the inside test would be a tie.
    const auto cellsAlong = [&](double extent) {
        return std::max<std::size_t>(1, std::size_t(std::ceil(extent / step)));
    };
    while (double(cellsAlong(size.x)) * double(cellsAlong(size.y)) * double(cellsAlong(size.z)) >
           double(options.maxVolumeCells))
        step *= 1.25;
    out.volumeStepMm = step;
    const std::size_t nx = cellsAlong(size.x), ny = cellsAlong(size.y), nz = cellsAlong(size.z);
    // Cells centred on the box's centre, so the grid sits symmetric in it.
    const Vec3 centre = 0.5 * (box.lo + box.hi);
    const Vec3 first = centre - 0.5 * step * Vec3{double(nx - 1), double(ny - 1), double(nz - 1)};
    // Which centres are inside: ray parity against the OAR's triangles
    // (field/Rasterization, exact but for centres within rounding of the
    // surface), where a signed distance to the OAR per centre of its box
    // cost as many closest-triangle queries as there are cells.
    VolumeGeometry cells;
    cells.size = {int(nx), int(ny), int(nz)};
    cells.spacingMm = {step, step, step};
    cells.originMm = {first.x, first.y, first.z};
    std::vector<Vec3> inside;
    for (const std::size_t n : voxelsInsideSolid(oar, PlaneFrame{}, cells)) {
        const std::size_t i = n % nx, j = (n / nx) % ny, k = n / (nx * ny);
        inside.push_back(first + step * Vec3{double(i), double(j), double(k)});
    }
    // Progress: the volume's queries to 80 %, then the surface's (fewer).
    auto volumeDone = [&](std::size_t k) {
        if (options.progress)
            options.progress(0.8 * double(k) / double(std::max<std::size_t>(1, inside.size())));
    };
    const std::vector<double> toTarget =
        signedDistances(scene, kernel.get(), 1, inside, volumeDone);
    out.volume = sorted(toTarget, std::vector<double>(inside.size(), step * step * step));

    // Surface: the centroids of cells of the OAR's triangles, by area.
    out.surfaceSpacingMm =
        cellSpacingWithinBudget({&oar}, options.surfaceSpacingMm, options.maxSurfaceCells);
    std::vector<Vec3> samples;
    std::vector<double> areas;
    for (const auto& t : oar.triangles)
        forEachCell(oar.points[t[0]], oar.points[t[1]], oar.points[t[2]], out.surfaceSpacingMm,
                    [&](const Vec3& p, double area) {
                        samples.push_back(p);
                        areas.push_back(area);
                    });
    auto surfaceDone = [&](std::size_t k) {
        if (options.progress)
            options.progress(0.8 +
                             0.2 * double(k) / double(std::max<std::size_t>(1, samples.size())));
    };
    out.surface = sorted(signedDistances(scene, kernel.get(), 1, samples, surfaceDone), areas);
    return out;
}

}  // namespace dfrecon
