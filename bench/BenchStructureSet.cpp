// dfrecon-bench structure-set: whole structure sets, every ROI, as
// `dfrecon reconstruct --all` makes them (the surface reconstructed and
// checked as a file holds it), against the route users take today, timed in
// the same run: rasterise each ROI onto a grid of 0.5 mm pixels and the
// planes' spacing, then marching cubes (rasterBaseline in
// recon/MarchingCubesBaselines). Lines per set: dfrecon
// (seconds, valid solids, worst deviation from the contour-implied volume)
// and rasterise+mc (seconds, valid solids, the same deviation); the
// dfrecon line carries the speed ratio.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "app/OrderedParallel.hpp"
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
};

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
    std::vector<std::unique_ptr<ocl::Runtime>> runtimes(jobs);
    for (auto& runtime : runtimes) runtime = std::make_unique<ocl::Runtime>(device);
    SetResult ours, baseline;
    ours.seconds = bestSeconds(1, [&] {
        app::forEachInOrder(
            rois.size(), jobs,
            [&](std::size_t i, std::size_t worker) {
                return reconstructSurface(*runtimes[worker], *rois[i]).check;
            },
            [&](std::size_t i, const MeshCheckReport& check) {
                addRoi(ours, check, contourVolumeMm3(*rois[i]));
            });
    });
    // The baseline route ends with the marched surface; checking it is ours.
    std::vector<TriangleSoup> marched(rois.size());
    baseline.seconds = bestSeconds(1, [&] {
        app::forEachInOrder(
            rois.size(), jobs,
            [&](std::size_t i, std::size_t) { return rasterBaseline(*rois[i], kRasterPixelMm); },
            [&](std::size_t i, TriangleSoup soup) { marched[i] = std::move(soup); });
    });
    for (std::size_t i = 0; i < rois.size(); ++i)
        addRoi(baseline, checkMesh(marched[i]), contourVolumeMm3(*rois[i]));
    auto line = [&](const char* system, const SetResult& r) {
        nlohmann::ordered_json j{
            {"bench", "structure-set"},   {"case", name},
            {"system", system},           {"size", r.rois},
            {"seconds", r.seconds},       {"validSolids", r.valid},
            {"triangles", r.triangles},   {"worstVolumeDeviationPct", 100 * r.worstVolumeDeviation},
            {"within1Pct", r.within1Pct}, {"jobs", jobs}};
        if (&r == &ours) j["speedupOverBaseline"] = baseline.seconds / ours.seconds;
        std::cout << j.dump() << std::endl;
    };
    line("dfrecon", ours);
    line("rasterise+mc", baseline);
}

}  // namespace

int benchStructureSet(const std::string& device) {
    const std::filesystem::path brodmann =
        std::filesystem::path(DFRECON_SHARED_DATA) / "brodmann-rtstruct.dcm";
    const std::filesystem::path kmeans =
        std::filesystem::path(DFRECON_FIXTURES) / "kmeans_axial" / "rtstruct.dcm";
    for (const auto& [name, path] : {std::pair{"brodmann 41 ROIs, 2 mm", brodmann},
                                     std::pair{"kmeans_axial 7 ROIs", kmeans}}) {
        if (!std::filesystem::exists(path)) {
            std::cout << nlohmann::ordered_json{{"bench", "structure-set"},
                                                {"case", name},
                                                {"skipped", path.string() + " not found"}}
                             .dump()
                      << std::endl;
            continue;
        }
        benchSet(device, name, readRtStruct(path.string()).contours);
    }
    // Many contours per plane, as a CT bone structure has.
    benchSet(device, "200 blobs, 240x240x40 voxels of 0.5x0.5x2 mm",
             contoursFromLabels(manyBlobLabelVolume(7, 200, 240, 40)));
    return 0;
}

}  // namespace dfrecon::bench
