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

#include <nlohmann/json.hpp>

#include "bench/Benchmarks.hpp"
#include "geometry/MeshCheck.hpp"
#include "io/MaskContours.hpp"
#include "io/RtStruct.hpp"
#include "recon/MarchingCubesBaselines.hpp"
#include "recon/Reconstruction.hpp"
#include "shapes/RandomLabelVolumes.hpp"

namespace dfrecon::bench {

namespace {

constexpr double kRasterPixelMm = 0.5;

struct SetResult {
    double seconds = 0;
    std::size_t rois = 0, valid = 0, triangles = 0;
    double worstVolumeDeviation = 0;  // |volume / contour volume - 1|, worst ROI
};

void addRoi(SetResult& set, const MeshCheckReport& check, double contourVolume) {
    ++set.rois;
    set.valid += check.validSolid();
    set.triangles += check.triangles;
    if (contourVolume > 0)
        set.worstVolumeDeviation =
            std::max(set.worstVolumeDeviation, std::abs(check.volumeMm3 / contourVolume - 1));
}

void benchSet(ocl::Runtime& runtime, const std::string& name, const ContourSet& set) {
    SetResult ours, baseline;
    for (const Roi& roi : set.rois) {
        if (roi.slices.empty()) continue;
        const double contourVolume = contourVolumeMm3(roi);
        Reconstruction result;
        ours.seconds += bestSeconds(1, [&] { result = reconstructSurface(runtime, roi); });
        addRoi(ours, result.check, contourVolume);
        TriangleSoup marched;
        baseline.seconds += bestSeconds(1, [&] { marched = rasterBaseline(roi, kRasterPixelMm); });
        addRoi(baseline, checkMesh(marched), contourVolume);
    }
    auto line = [&](const char* system, const SetResult& r) {
        nlohmann::ordered_json j{
            {"bench", "structure-set"}, {"case", name},
            {"system", system},         {"size", r.rois},
            {"seconds", r.seconds},     {"validSolids", r.valid},
            {"triangles", r.triangles}, {"worstVolumeDeviationPct", 100 * r.worstVolumeDeviation}};
        if (&r == &ours) j["speedupOverBaseline"] = baseline.seconds / ours.seconds;
        std::cout << j.dump() << std::endl;
    };
    line("dfrecon", ours);
    line("rasterise+mc", baseline);
}

}  // namespace

int benchStructureSet(const std::string& device) {
    ocl::Runtime runtime(device);
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
        benchSet(runtime, name, readRtStruct(path.string()).contours);
    }
    // Many contours per plane, as a CT bone structure has.
    benchSet(runtime, "200 blobs, 240x240x40 voxels of 0.5x0.5x2 mm",
             contoursFromLabels(manyBlobLabelVolume(7, 200, 240, 40)));
    return 0;
}

}  // namespace dfrecon::bench
