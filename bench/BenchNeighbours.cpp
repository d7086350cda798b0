// Neighbours kept apart (dfrecon-bench neighbours): structure sets whose
// ROIs touch without overlapping on their planes (the shared Brodmann
// atlas, the split ball of tests/data/neighbours), every ROI reconstructed
// on its own (the baseline: what `reconstruct --all` writes by default and
// wrote before) and then moved apart. Quality per line: the overlap of the
// pairs that met, measured exactly (compare's overlapOf), in total and the
// largest, the pairs within 1 mm³, and the worst ROI volume against its
// contour-implied volume; seconds: the separation alone.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>

#include <nlohmann/json.hpp>

#include "bench/Benchmarks.hpp"
#include "cl/WorkerRuntimes.hpp"
#include "dfrecon/Contours.hpp"
#include "dfrecon/Reconstruct.hpp"
#include "geometry/OrderedParallel.hpp"

namespace dfrecon::bench {

namespace {

// The figures of one route over a set.
nlohmann::ordered_json measure(const std::string& caseName, const char* system,
                               const std::vector<const Roi*>& rois,
                               std::vector<RoiSurface>& surfaces,
                               const NeighbourSeparation& separation, double seconds) {
    std::vector<RoiSurface*> all;
    for (RoiSurface& s : surfaces) all.push_back(&s);
    std::vector<double> overlaps;
    for (const std::optional<Overlap>& overlap : neighbourOverlaps(separation, all))
        overlaps.push_back(overlap ? overlap->intersectionMm3 : 0.0);
    double total = 0, largest = 0, worstVolume = 0;
    std::size_t within = 0, met = 0;
    std::string largestPair;
    for (std::size_t p = 0; p < overlaps.size(); ++p) {
        const NeighbourPair& pair = separation.pairs[p];
        if (pair.overlapOnPlanes) continue;
        ++met;
        total += overlaps[p];
        within += overlaps[p] <= 1.0;
        if (overlaps[p] > largest) {
            largest = overlaps[p];
            largestPair = rois[pair.a]->name + "/" + rois[pair.b]->name;
        }
    }
    for (std::size_t i = 0; i < rois.size(); ++i)
        worstVolume = std::max(
            worstVolume, std::abs(surfaces[i].check.volumeMm3 / surfaces[i].contourVolumeMm3 - 1));
    return {{"bench", "neighbours"},
            {"case", caseName},
            {"system", system},
            {"seconds", seconds},
            {"size", rois.size()},
            {"pairs_met", met},
            {"overlap_total_mm3", total},
            {"overlap_largest_mm3", largest},
            {"largest_pair", largestPair},
            {"pairs_within_1mm3", within},
            {"worst_volume_deviation_percent", 100 * worstVolume}};
}

}  // namespace

int benchNeighbours(const std::string& device) {
    const std::filesystem::path sets[] = {
        std::filesystem::path(DFRECON_SOURCE_DIR) / "tests/data/neighbours/split-ball.slices",
        std::filesystem::path(DFRECON_SHARED_DATA) / "brodmann-rtstruct.dcm"};
    for (const std::filesystem::path& file : sets) {
        if (!std::filesystem::exists(file)) {
            std::cerr << "neighbours: " << file << " missing, skipped\n";
            continue;
        }
        const ContoursRead read = readContours(file.string());
        std::vector<const Roi*> rois;
        for (const Roi& roi : read.contours.rois)
            if (!roi.defect && !roi.slices.empty()) rois.push_back(&roi);
        const std::size_t jobs = defaultJobs(rois.size());
        ocl::WorkerRuntimes runtimes(device, jobs);
        std::vector<RoiSurface> independent(rois.size());
        forEachInOrder(
            rois.size(), jobs,
            [&](std::size_t i, std::size_t worker) {
                return reconstructRoi(runtimes[worker], *rois[i]);
            },
            [&](std::size_t i, RoiSurface surface) { independent[i] = std::move(surface); });
        std::vector<RoiSurface> apart = independent;
        auto pointers = [](std::vector<RoiSurface>& surfaces) {
            std::vector<RoiSurface*> all;
            for (RoiSurface& s : surfaces) all.push_back(&s);
            return all;
        };
        NeighbourSeparationOptions findOnly;
        findOnly.move = false;
        const NeighbourSeparation found =
            keepNeighboursApart(runtimes[0], rois, pointers(independent), findOnly);
        const NeighbourSeparation moved = keepNeighboursApart(runtimes[0], rois, pointers(apart));
        const std::string caseName = file.filename().string();
        std::cout << measure(caseName, "independent (baseline)", rois, independent, found,
                             found.seconds)
                         .dump()
                  << "\n"
                  << measure(caseName, "dfrecon apart", rois, apart, moved, moved.seconds).dump()
                  << "\n"
                  << std::flush;
    }
    return 0;
}

}  // namespace dfrecon::bench
