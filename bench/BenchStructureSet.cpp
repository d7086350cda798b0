// dfrecon-bench structure-set: whole structure sets, every ROI, as
// `dfrecon reconstruct --all` makes them (the surface reconstructed and
// checked as a file holds it), against the route users take today, timed in
// the same run: rasterise each ROI onto a grid of 0.5 mm pixels and the
// planes' spacing, then marching cubes (rasterBaseline in
// recon/MarchingCubesBaselines). Lines per set: dfrecon
// (seconds, valid solids, worst deviation from the contour-implied volume)
// and rasterise+mc (seconds, valid solids, the same deviation), each with
// the process's peak memory during that route; the dfrecon line carries the
// speed ratio. The sets: the shared Brodmann atlas, plastimatch's k-means
// fixture, a head CT's BONE alone and with BODY and AIRWAY (build/bench-
// fixtures/ct_head, scripts/ct_structures.py; make bench makes it), and 200 blobs in one ROI.
#include <malloc.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "app/OrderedParallel.hpp"
#include "app/WorkerRuntimes.hpp"
#include "baselines/MarchingCubesBaselines.hpp"
#include "bench/Benchmarks.hpp"
#include "geometry/MeshCheck.hpp"
#include "io/MaskContours.hpp"
#include "io/RtStruct.hpp"
#include "recon/Reconstruction.hpp"
#include "shapes/RandomLabelVolumes.hpp"

namespace dfrecon::bench {

namespace {

constexpr double kRasterPixelMm = 0.5;

struct SetResult {
    double seconds = 0;
    std::size_t rois = 0, valid = 0, triangles = 0;
    double worstVolumeDeviation = 0;  // |volume / contour volume - 1|, worst ROI
    std::size_t within1Pct = 0;       // ROIs within 1 % of their contour volume
    double peakMemoryMb = 0;          // the process's, during the route
};

// The process's peak resident memory since the last reset, in MB (Linux's
// VmHWM; 0 where /proc does not say).
double peakMemoryMb() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // kB
    return 0;
}

// Starts a new peak at the current resident size (Linux >= 4.0: writing 5
// to clear_refs resets VmHWM), so each route's peak is its own.
// What the heap freed goes back to the system first (glibc keeps it
// otherwise, and the route before would count in this one's peak).
void resetPeakMemory() {
    malloc_trim(0);
    std::ofstream("/proc/self/clear_refs") << "5";
}

void addRoi(SetResult& set, const MeshCheckReport& check, double contourVolume) {
    ++set.rois;
    set.valid += check.validSolid();
    set.triangles += check.triangles;
    if (contourVolume > 0) {
        const double deviation = std::abs(check.volumeMm3 / contourVolume - 1);
        set.worstVolumeDeviation = std::max(set.worstVolumeDeviation, deviation);
        set.within1Pct += deviation <= 0.01;
    }
}

// Both routes run the set's ROIs `jobs` at a time, as `dfrecon reconstruct
// --all` does (each worker with its own OpenCL queue), and are timed over
// the whole set.
void benchSet(const std::string& device, const std::string& name, const ContourSet& set) {
    std::vector<const Roi*> rois;
    for (const Roi& roi : set.rois)
        if (!roi.slices.empty()) rois.push_back(&roi);
    const std::size_t jobs = app::defaultJobs(rois.size());
    app::WorkerRuntimes runtimes(device, jobs);  // as reconstruct --all opens them
    SetResult ours, baseline;
    resetPeakMemory();
    ours.seconds = bestSeconds(1, [&] {
        app::forEachInOrder(
            rois.size(), jobs,
            [&](std::size_t i, std::size_t worker) {
                return reconstructSurface(runtimes[worker], *rois[i]).check;
            },
            [&](std::size_t i, const MeshCheckReport& check) {
                addRoi(ours, check, contourVolumeMm3(*rois[i]));
            });
    });
    ours.peakMemoryMb = peakMemoryMb();
    // The baseline route ends with the marched surface; checking it is ours.
    std::vector<TriangleSoup> marched(rois.size());
    resetPeakMemory();
    baseline.seconds = bestSeconds(1, [&] {
        app::forEachInOrder(
            rois.size(), jobs,
            [&](std::size_t i, std::size_t) { return rasterBaseline(*rois[i], kRasterPixelMm); },
            [&](std::size_t i, TriangleSoup soup) { marched[i] = std::move(soup); });
    });
    baseline.peakMemoryMb = peakMemoryMb();
    for (std::size_t i = 0; i < rois.size(); ++i)
        addRoi(baseline, checkMesh(marched[i]), contourVolumeMm3(*rois[i]));
    auto line = [&](const char* system, const SetResult& r) {
        nlohmann::ordered_json j{{"bench", "structure-set"},
                                 {"case", name},
                                 {"system", system},
                                 {"size", r.rois},
                                 {"seconds", r.seconds},
                                 {"validSolids", r.valid},
                                 {"triangles", r.triangles},
                                 {"worstVolumeDeviationPct", 100 * r.worstVolumeDeviation},
                                 {"within1Pct", r.within1Pct},
                                 {"jobs", jobs},
                                 {"peakMemoryMb", r.peakMemoryMb}};
        if (&r == &ours) j["speedupOverBaseline"] = baseline.seconds / ours.seconds;
        std::cout << j.dump() << std::endl;
    };
    line("dfrecon", ours);
    line("rasterise+mc", baseline);
}

}  // namespace

int benchStructureSet(const std::string& device) {
    const std::filesystem::path fixtures(DFRECON_FIXTURES);
    const std::filesystem::path brodmann =
        std::filesystem::path(DFRECON_SHARED_DATA) / "brodmann-rtstruct.dcm";
    const std::filesystem::path kmeans = fixtures / "kmeans_axial" / "rtstruct.dcm";
    const std::filesystem::path head =
        std::filesystem::path(DFRECON_BENCH_FIXTURES) / "ct_head" / "rtstruct.dcm";
    // A case: a file and the ROIs of it to reconstruct (empty: all).
    struct Case {
        const char* name;
        std::filesystem::path path;
        std::vector<std::string> rois;
    };
    const Case cases[] = {
        {"brodmann 41 ROIs, 2 mm", brodmann, {}},
        {"kmeans_axial 7 ROIs", kmeans, {}},
        {"head CT bone, 1.5 mm", head, {"BONE"}},
        {"head CT body, airway, bone, 1.5 mm", head, {}},
    };
    for (const Case& c : cases) {
        if (!std::filesystem::exists(c.path)) {
            std::cout << nlohmann::ordered_json{{"bench", "structure-set"},
                                                {"case", c.name},
                                                {"skipped", c.path.string() +
                                                                " not found (make bench makes it)"}}
                             .dump()
                      << std::endl;
            continue;
        }
        ContourSet set = readRtStruct(c.path.string()).contours;
        if (!c.rois.empty())
            set.rois.erase(std::remove_if(set.rois.begin(), set.rois.end(),
                                          [&](const Roi& roi) {
                                              return std::find(c.rois.begin(), c.rois.end(),
                                                               roi.name) == c.rois.end();
                                          }),
                           set.rois.end());
        benchSet(device, c.name, set);
    }
    // Many contours per plane in one ROI.
    benchSet(device, "200 blobs, 240x240x40 voxels of 0.5x0.5x2 mm",
             contoursFromLabels(manyBlobLabelVolume(7, 200, 240, 40)));
    return 0;
}

}  // namespace dfrecon::bench
