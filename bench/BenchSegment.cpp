// Geodesic distances and segmentation (segment/). Rows:
//  - geodesic spheres of ~10K, ~100K and ~1M vertices, one source: fast
//    marching with and without obtuse-angle unfolding (these spheres have
//    no obtuse angles, so both must agree), the OpenCL fast iterative
//    method and its C++ reference; error against the great-circle distance
//    in % of the radius; fast marching's throughput in vertices per second
//    (solve only; building the stencils is setup_seconds);
//  - the ~100K sphere with its vertices jittered (irregular, obtuse
//    triangles): the same rows;
//  - a flat grid of 136° triangles: unfolding against none, error against
//    the Euclidean distance in % of the grid's width;
//  - bunny00, armadillo, refined_elephant from libcgal-demo (no analytic
//    reference): fast marching's time, and the FIM's and unfolding-off
//    distances against fast marching's, in % of the bounding-box diagonal;
//  - Lloyd iterations on a tessellated cube (10 seeds, attractive speed)
//    and on the bunny (20 seeds): iterations, energy and region-area spread.
// Each row names what its errors are measured against in "reference".
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <numeric>

#include <nlohmann/json.hpp>

#include "bench/Benchmarks.hpp"
#include "io/mesh/MeshIO.hpp"
#include "segment/EikonalFim.hpp"
#include "segment/Segmentation.hpp"
#include "shapes/MeshShapes.hpp"

namespace dfrecon::bench {

namespace {

using Json = nlohmann::ordered_json;

/// A row's errors against its reference (NaN: none measured), in % of the
/// reference's scale, and the reference's name.
struct Accuracy {
    double meanErrPct = NAN, maxErrPct = NAN;
    std::string reference = "none";
};

void printRow(const std::string& caseName, const std::string& system, double seconds, int vertices,
              const Accuracy& accuracy, Json extra = Json::object()) {
    const double meanErrPct = accuracy.meanErrPct, maxErrPct = accuracy.maxErrPct;
    const std::string& reference = accuracy.reference;
    Json row{{"bench", "segment"},
             {"case", caseName},
             {"system", system},
             {"seconds", seconds},
             {"vertices", vertices},
             {"mean_err_pct", std::isfinite(meanErrPct) ? Json(meanErrPct) : Json(nullptr)},
             {"max_err_pct", std::isfinite(maxErrPct) ? Json(maxErrPct) : Json(nullptr)},
             {"reference", reference}};
    for (auto& [key, value] : extra.items()) row[key] = value;
    std::cout << row.dump() << std::endl;
}

struct Errors {
    double meanPct = 0, maxPct = 0;
};

/// |time − reference| in % of `scale`, over reached vertices.
template <class Reference>
Errors errorsPct(const std::vector<double>& time, double scale, Reference&& reference) {
    Errors e;
    std::size_t count = 0;
    for (std::size_t v = 0; v < time.size(); ++v) {
        if (!std::isfinite(time[v])) continue;
        const double d = std::abs(time[v] - reference(v));
        e.meanPct += d;
        e.maxPct = std::max(e.maxPct, d);
        ++count;
    }
    e.meanPct = 100 * e.meanPct / (double(std::max<std::size_t>(count, 1)) * scale);
    e.maxPct = 100 * e.maxPct / scale;
    return e;
}

double seconds(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The times a case's rows are held to: their name, the length whose % the
/// errors are in, and the time at each vertex.
struct ReferenceTimes {
    std::string name;
    double scale = 1;
    std::function<double(std::size_t)> at;
};

/// Fast marching (with and without unfolding) and the FIM (device and C++
/// reference) from vertex `source`, errors against `exact`.
void solverRows(ocl::Runtime& runtime, const std::string& caseName, const MeshGraph& graph,
                int source, const ReferenceTimes& exact, bool runFim) {
    const double scale = exact.scale;
    const std::string& referenceName = exact.name;
    const std::function<double(std::size_t)>& reference = exact.at;
    const int n = graph.vertexCount();
    const std::vector<GeodesicSource> sources{{source, 0.0, 0}};
    auto start = std::chrono::steady_clock::now();
    const UpdateStencils stencils(graph);
    const double setup = seconds(start);
    GeodesicField marched;
    const int runs = n > 500000 ? 1 : 3;
    double t = bestSeconds(runs, [&] { marched = FastMarching(stencils).solve(sources); });
    const Errors fm = errorsPct(marched.time, scale, reference);
    printRow(caseName, "fast-marching", t, n, {fm.meanPct, fm.maxPct, referenceName},
             {{"vertices_per_second", n / t},
              {"setup_seconds", setup},
              {"obtuse_corners", stencils.obtuseCorners()},
              {"unfold_failures", stencils.unfoldFailures()}});

    UnfoldOptions plain;
    plain.unfoldObtuse = false;
    start = std::chrono::steady_clock::now();
    const UpdateStencils obtuse(graph, plain);
    const double plainSetup = seconds(start);
    GeodesicField unfoldless;
    t = bestSeconds(runs, [&] { unfoldless = FastMarching(obtuse).solve(sources); });
    const Errors nu = errorsPct(unfoldless.time, scale, reference);
    printRow(caseName, "fast-marching-no-unfold", t, n, {nu.meanPct, nu.maxPct, referenceName},
             {{"vertices_per_second", n / t}, {"setup_seconds", plainSetup}});
    if (!runFim) return;

    FimStats stats;
    GeodesicField iterated;
    t = bestSeconds(runs,
                    [&] { iterated = eikonalFimReference(stencils, sources, {}, {}, &stats); });
    const Errors ref = errorsPct(iterated.time, scale, reference);
    const Errors refVsFm =
        errorsPct(iterated.time, scale, [&](std::size_t v) { return marched.time[v]; });
    printRow(caseName, "fim-cpp-reference", t, n, {ref.meanPct, ref.maxPct, referenceName},
             {{"iterations", stats.iterations}, {"max_diff_vs_fm_pct", refVsFm.maxPct}});

    start = std::chrono::steady_clock::now();
    EikonalFim fim(runtime, stencils);
    const double upload = seconds(start);
    t = bestSeconds(runs, [&] { iterated = fim.solve(sources, &stats); });
    const Errors dev = errorsPct(iterated.time, scale, reference);
    const Errors devVsFm =
        errorsPct(iterated.time, scale, [&](std::size_t v) { return marched.time[v]; });
    printRow(caseName, "fim-opencl", t, n, {dev.meanPct, dev.maxPct, referenceName},
             {{"iterations", stats.iterations},
              {"setup_seconds", upload},
              {"device", runtime.device().deviceName},
              {"double_precision", stats.doublePrecision},
              {"max_diff_vs_fm_pct", devVsFm.maxPct}});
}

void segmentationRow(const std::string& caseName, const MeshGraph& graph, int regions) {
    SegmentOptions options;
    options.regions = regions;
    options.speed = SpeedKind::EdgeAttractive;
    const Segmentation s = segmentMesh(graph, options);
    std::vector<double> areas;
    for (const RegionReport& r : s.regions) areas.push_back(r.areaMm2);
    const double mean = std::accumulate(areas.begin(), areas.end(), 0.0) / double(areas.size());
    double variance = 0;
    for (double a : areas) variance += (a - mean) * (a - mean) / double(areas.size());
    int disks = 0;
    for (const RegionReport& r : s.regions) disks += r.disk ? 1 : 0;
    printRow(caseName, "geodesic-lloyd", s.seconds, graph.vertexCount(), {},
             {{"regions", s.regions.size()},
              {"seeds_added", s.seedsAdded},
              {"iterations", s.iterations},
              {"converged", s.converged},
              {"energy_first", s.energy.front()},
              {"energy_last", s.energy.back()},
              {"area_mean", mean},
              {"area_variance", variance},
              {"area_cv", std::sqrt(variance) / mean},
              {"disk_regions", disks}});
}

}  // namespace

int benchSegment(const std::string& device) {
    int status = 0;
    ocl::Runtime runtime(device);
    {  // Build the FIM kernels once, untimed.
        const MeshGraph warm = MeshGraph::fromSoup(geodesicSphere(2));
        const UpdateStencils stencils(warm);
        EikonalFim(runtime, stencils).solve({{0, 0.0, 0}});
    }
    for (int frequency : {32, 100, 316}) {
        const MeshGraph graph = MeshGraph::fromSoup(geodesicSphere(frequency));
        const Vec3 s = graph.point(0);
        solverRows(runtime, "sphere " + std::to_string(graph.vertexCount()) + " vertices", graph, 0,
                   {"great-circle distance, % of radius", 1.0,
                    [&](std::size_t v) {
                        return std::acos(std::clamp(dot(s, graph.point(int(v))), -1.0, 1.0));
                    }},
                   true);
    }
    {
        // The same sphere with every vertex moved at random by up to 0.35 of
        // an edge along each axis and put back on the sphere: irregular, with
        // obtuse triangles, like a scanned mesh.
        const TriangleSoup soup = jitteredGeodesicSphere(100, 0.35);
        const MeshGraph graph = MeshGraph::fromSoup(soup);
        const Vec3 s = graph.point(0);
        solverRows(runtime, "jittered sphere " + std::to_string(graph.vertexCount()) + " vertices",
                   graph, 0,
                   {"great-circle distance, % of radius", 1.0,
                    [&](std::size_t v) {
                        return std::acos(std::clamp(dot(s, graph.point(int(v))), -1.0, 1.0));
                    }},
                   true);
    }
    {
        const int columns = 160, rows = 640;
        const double dx = 1.0 / columns, dy = 0.2 * dx;  // 136° apex angles
        const MeshGraph graph = MeshGraph::fromSoup(staggeredGrid(columns, rows, dx, dy));
        const int source = (rows / 2) * (columns + 1) + columns / 2;
        const Vec3 s = graph.point(source);
        solverRows(runtime, "flat grid of 136-degree triangles", graph, source,
                   {"euclidean distance, % of grid width", 1.0,
                    [&](std::size_t v) { return length(graph.point(int(v)) - s); }},
                   false);
    }
    for (const std::string name : {"bunny00", "armadillo", "refined_elephant"}) {
        const std::filesystem::path path =
            std::filesystem::path(DFRECON_FIXTURES) / "meshes" / (name + ".off");
        if (!std::filesystem::exists(path)) {
            std::cerr << path << " is missing: run make setup\n";
            status = 1;
            continue;
        }
        const MeshGraph graph = MeshGraph::fromMesh(readMesh(path.string()));
        Vec3 lo = graph.point(0), hi = lo;
        for (const Vec3& p : graph.points()) {
            lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
            hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
        }
        // Reference: fast marching itself (computed in solverRows' first row).
        const UpdateStencils stencils(graph);
        const GeodesicField marched = FastMarching(stencils).solve({{0, 0.0, 0}});
        solverRows(runtime, name, graph, 0,
                   {"fast marching with unfolding, % of bounding-box diagonal", length(hi - lo),
                    [&](std::size_t v) { return marched.time[v]; }},
                   true);
        if (name == "bunny00") segmentationRow("lloyd bunny00, 20 seeds", graph, 20);
    }
    segmentationRow("lloyd cube 5402 vertices, 10 seeds", MeshGraph::fromSoup(tessellatedCube(30)),
                    10);
    return status;
}

}  // namespace dfrecon::bench
