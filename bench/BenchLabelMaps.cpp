// Label maps against the surface they stand for (dfrecon-bench label-maps):
// every ROI of 1 cc or more of the shared structure sets (three clinical
// exports and the atlas truth set, 3 mm planes), rasterized on rasterize
// --voxel-mm's grid at 1 and 0.5 mm by the reconstructed solid (rasterize's
// default) and by the 3D distance field (the baseline, `--inside field`).
// Quality: the label map's volume against the surface's, in percent.
#include <cmath>
#include <filesystem>
#include <iostream>

#include <nlohmann/json.hpp>

#include "bench/Benchmarks.hpp"
#include "dfrecon/Contours.hpp"
#include "dfrecon/Field.hpp"
#include "dfrecon/Reconstruct.hpp"

namespace dfrecon::bench {

int benchLabelMaps(const std::string& device) {
    ocl::Runtime runtime(device);
    const std::filesystem::path data(DFRECON_SHARED_DATA);
    for (const std::filesystem::path& file : {data / "clinical" / "ibsi-phantom-gtv-rtstruct.dcm",
                                              data / "clinical" / "pinnacle-hn-rtstruct.dcm",
                                              data / "clinical" / "sarcoma-mr-oblique-rtstruct.dcm",
                                              data / "truth-brodmann-axial-rtstruct.dcm"}) {
        if (!std::filesystem::exists(file)) {
            std::cerr << "label-maps: " << file << " missing, skipped\n";
            continue;
        }
        const ContoursRead read = readContours(file.string());
        for (const Roi& roi : read.contours.rois) {
            if (roi.defect || roi.slices.empty()) continue;
            RoiSurface solid;
            const double reconstructSeconds =
                bestSeconds(1, [&] { solid = reconstructRoi(runtime, roi); });
            if (!solid.check.validSolid() || solid.check.volumeMm3 < 1000) continue;
            for (const double voxelMm : {1.0, 0.5}) {
                const VolumeGeometry grid = gridAroundRois({&roi}, voxelMm);
                const double voxelMm3 = std::pow(voxelMm, 3);
                std::size_t fromSolid = 0, fromField = 0;
                const double solidSeconds = bestSeconds(
                    1, [&] { fromSolid = roiSolidVoxelsInside(roi, solid, grid).size(); });
                const double fieldSeconds =
                    bestSeconds(1, [&] { fromField = roiVoxelsInside(runtime, roi, grid).size(); });
                const std::string caseName = file.filename().string() + " " + roi.name + ", " +
                                             std::to_string(voxelMm).substr(0, 3) + " mm voxels";
                const auto row = [&](const char* system, double seconds, std::size_t voxels) {
                    const double volumeMm3 = double(voxels) * voxelMm3;
                    return nlohmann::ordered_json{
                        {"bench", "label-maps"},
                        {"case", caseName},
                        {"system", system},
                        {"seconds", seconds},
                        {"size", grid.voxelCount()},
                        {"surface_cc", solid.check.volumeMm3 / 1000},
                        {"label_map_cc", volumeMm3 / 1000},
                        {"volume_error_percent", 100 * (volumeMm3 / solid.check.volumeMm3 - 1)}};
                };
                nlohmann::ordered_json ours = row("dfrecon solid", solidSeconds, fromSolid);
                ours["reconstruct_seconds"] = reconstructSeconds;
                std::cout << ours.dump() << "\n"
                          << row("distance field", fieldSeconds, fromField).dump() << std::endl;
            }
        }
    }
    return 0;
}

}  // namespace dfrecon::bench
