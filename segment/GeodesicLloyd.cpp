#include "segment/GeodesicLloyd.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dfrecon {

namespace {

Vec3 vertexNormal(const MeshGraph& graph, int v) {
    Vec3 sum{};
    for (int t : graph.trianglesAround(v)) {
        const auto& tri = graph.triangle(t);
        const Vec3 n = cross(graph.point(tri[1]) - graph.point(tri[0]),
                             graph.point(tri[2]) - graph.point(tri[0]));
        // Orientation may be inconsistent: align with the running sum.
        sum = sum + (dot(sum, n) < 0 ? -1.0 : 1.0) * n;
    }
    const double l = length(sum);
    return l > 0 ? (1 / l) * sum : Vec3{0, 0, 1};
}

Vec3 normalised(Vec3 v) {
    const double l = length(v);
    return l > 0 ? (1 / l) * v : Vec3{};
}

double fieldEnergy(const GeodesicField& field, const std::vector<double>& vertexAreas) {
    double energy = 0;
    for (std::size_t v = 0; v < vertexAreas.size(); ++v)
        if (std::isfinite(field.time[v])) energy += vertexAreas[v] * field.time[v] * field.time[v];
    return energy;
}

}  // namespace

RegionCentre regionCentre(const MeshGraph& graph, const FastMarching& marching,
                          const std::vector<double>& vertexAreas,
                          const std::vector<int>& regionVertices, int seed, int steps) {
    const std::size_t n = std::size_t(graph.vertexCount());
    std::vector<char> inRegion(n, 0);
    for (int v : regionVertices) inRegion[std::size_t(v)] = 1;
    std::vector<Vec3> direction(n);
    std::vector<char> hasDirection(n, 0);
    std::vector<int> order;
    std::vector<UpwindRecord> upwind;
    std::vector<int> visited;
    int w = seed, best = seed;
    double bestEnergy = kUnreached;
    for (int step = 0; step <= steps; ++step) {
        visited.push_back(w);
        const bool seedInRegion = inRegion[std::size_t(w)] != 0;
        inRegion[std::size_t(w)] = 1;  // so the march stops once the region is done
        order.clear();
        MarchOptions march;
        march.stopWhenFinal = &inRegion;
        march.finalOrder = &order;
        march.upwind = &upwind;
        const GeodesicField field = marching.solve({{w, 0.0, 0}}, march);
        inRegion[std::size_t(w)] = seedInRegion;
        double e = 0, area = 0;
        for (int x : regionVertices) {
            const double t = field.time[std::size_t(x)];
            e += vertexAreas[std::size_t(x)] * t * t;
            area += vertexAreas[std::size_t(x)];
        }
        if (!(e < bestEnergy)) break;  // the step made it worse: keep the best
        best = w;
        bestEnergy = e;
        if (step == steps || area <= 0) break;

        // Back-traced geodesic directions at w, carried along the upwind records.
        const Vec3 pw = graph.point(w), normal = vertexNormal(graph, w);
        const auto tangentTo = [&](int x) {
            const Vec3 d = graph.point(x) - pw;
            return normalised(d - dot(d, normal) * normal);
        };
        for (int x : order) hasDirection[std::size_t(x)] = 0;
        for (int x : order) {
            if (x == w) continue;
            const UpwindRecord& r = upwind[std::size_t(x)];
            Vec3 d{};
            if (r.a >= 0 && r.a != w && r.b != w && hasDirection[std::size_t(r.a)] &&
                hasDirection[std::size_t(r.b)])
                d = normalised((1 - r.weightB) * direction[std::size_t(r.a)] +
                               r.weightB * direction[std::size_t(r.b)]);
            if (length(d) == 0) d = tangentTo(x);
            direction[std::size_t(x)] = d;
            hasDirection[std::size_t(x)] = 1;
        }
        // The mean of the log map d·n_w over the region: −∇E_i / (2·area).
        Vec3 mean{};
        for (int x : regionVertices)
            if (x != w && hasDirection[std::size_t(x)])
                mean = mean + (vertexAreas[std::size_t(x)] * field.time[std::size_t(x)]) *
                                  direction[std::size_t(x)];
        mean = (1 / area) * mean;
        int next = w;
        double nearest = dot(mean, mean);  // staying at w: log map 0
        for (int x : regionVertices) {
            if (x == w || !hasDirection[std::size_t(x)]) continue;
            const Vec3 diff = field.time[std::size_t(x)] * direction[std::size_t(x)] - mean;
            if (dot(diff, diff) < nearest) {
                nearest = dot(diff, diff);
                next = x;
            }
        }
        if (next == w || std::find(visited.begin(), visited.end(), next) != visited.end()) break;
        w = next;
    }
    return {best, bestEnergy};
}

LloydResult geodesicLloyd(const MeshGraph& graph, const FastMarching& marching,
                          std::vector<int> seeds, const LloydOptions& options) {
    if (seeds.empty()) throw std::invalid_argument("geodesic Lloyd needs at least one seed");
    for (int s : seeds)
        if (s < 0 || s >= graph.vertexCount())
            throw std::invalid_argument("seed vertex " + std::to_string(s) + " out of range");
    const std::vector<double> vertexAreas = graph.vertexAreas();
    LloydResult result;
    int addBudget = options.maxAddedSeeds >= 0 ? options.maxAddedSeeds : int(seeds.size());

    const auto computeRegions = [&] {
        std::vector<GeodesicSource> sources;
        for (std::size_t i = 0; i < seeds.size(); ++i) sources.push_back({seeds[i], 0.0, int(i)});
        result.field = marching.solve(sources);
        result.regions = geodesicVoronoi(graph, marching, result.field, int(seeds.size()));
    };
    // Regions, then a seed for each region that is not a disk, until all are
    // disks or the budget is spent.
    const auto regionsWithDisks = [&] {
        computeRegions();
        while (options.diskConstraint) {
            const std::vector<RegionTopology> topology =
                regionTopology(graph, result.regions.faceRegion, int(seeds.size()));
            std::vector<int> added;
            result.nonDiskRegions = 0;
            for (int r = 0; r < int(topology.size()); ++r) {
                if (topology[std::size_t(r)].faces == 0 || topology[std::size_t(r)].isDisk())
                    continue;
                ++result.nonDiskRegions;
                if (int(added.size()) >= addBudget) continue;
                int farthest = -1;
                for (int v = 0; v < graph.vertexCount(); ++v)
                    if (result.field.label[std::size_t(v)] == r &&
                        (farthest < 0 || result.field.time[std::size_t(v)] >
                                             result.field.time[std::size_t(farthest)]))
                        farthest = v;
                if (farthest >= 0 && result.field.time[std::size_t(farthest)] > 0)
                    added.push_back(farthest);
            }
            if (added.empty()) break;
            seeds.insert(seeds.end(), added.begin(), added.end());
            addBudget -= int(added.size());
            result.seedsAdded += int(added.size());
            computeRegions();
        }
    };

    regionsWithDisks();
    result.energy.push_back(fieldEnergy(result.field, vertexAreas));
    std::vector<std::vector<int>> members;
    for (int iteration = 1; iteration <= options.maxIterations; ++iteration) {
        members.assign(seeds.size(), {});
        for (int v = 0; v < graph.vertexCount(); ++v) {
            const int label = result.field.label[std::size_t(v)];
            if (label >= 0) members[std::size_t(label)].push_back(v);
        }
        std::vector<int> moved = seeds;
        for (std::size_t i = 0; i < seeds.size(); ++i)
            if (!members[i].empty())
                moved[i] = regionCentre(graph, marching, vertexAreas, members[i], seeds[i],
                                        options.centerSteps)
                               .vertex;
        if (moved == seeds) {
            result.converged = true;
            break;
        }
        const std::vector<int> labelsBefore = result.field.label;
        seeds = moved;
        regionsWithDisks();
        result.energy.push_back(fieldEnergy(result.field, vertexAreas));
        result.iterations = iteration;
        if (options.onIteration) options.onIteration(iteration, options.maxIterations);
        if (result.field.label == labelsBefore) {
            result.converged = true;
            break;
        }
    }
    result.seeds = seeds;
    return result;
}

}  // namespace dfrecon
