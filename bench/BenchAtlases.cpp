// Whole atlases, every area (issue 66: "every ROI of at least 0.5 cc within
// 2 % of its contour volume ... on the atlases you generate"): every label
// of AAL and AICHA from Debian's mricron-data, smoothed and cut by planes
// (scripts/truth_sets.sh --whole, the truth sets' cutter), read as the program
// reads a user's file and reconstructed as `dfrecon reconstruct --all` does
// (default options, as many ROIs at a time as it runs). Each area's volume
// is set beside its contour volume (Σ area × thickness, what a planning
// system reports) and its true surface's, so an area beyond 2 % of its
// contour volume shows whether the contour volume or the surface is the
// one off. JSON lines: one per such area (0.5 cc or more), one summary
// per set.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "bench/Benchmarks.hpp"
#include "cl/WorkerRuntimes.hpp"
#include "dfrecon/Contours.hpp"
#include "geometry/OrderedParallel.hpp"
#include "recon/Reconstruction.hpp"

namespace dfrecon::bench {

namespace {

constexpr double kLeastMm3 = 500;      // the 0.5 cc
constexpr double kToleratedPct = 2.0;  // and its 2 %

/// The folder of atlas sets: made by scripts/truth_sets.sh --whole when missing.
std::filesystem::path atlasSetsDir() {
    const std::filesystem::path dir = std::filesystem::path(DFRECON_BUILD_DIR) / "atlas-sets";
    const std::string command = std::string("bash '") + DFRECON_SOURCE_DIR +
                                "/scripts/truth_sets.sh' --whole '" + dir.string() + "'";
    if (std::system(command.c_str()) != 0)
        throw std::runtime_error("atlases: " + command + " failed");
    return dir;
}

/// Each true surface's volume in mm³ by ROI name (set-surface-cc.txt: NAME CC).
std::map<std::string, double> trueVolumesMm3(const std::filesystem::path& file) {
    std::map<std::string, double> volumes;
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream fields(line);
        std::string name;
        double cc = 0;
        if (fields >> name >> cc) volumes[name] = 1000 * cc;
    }
    return volumes;
}

double percentOff(double value, double reference) {
    return 100 * (value / reference - 1);
}

}  // namespace

int benchAtlases(const std::string& device) {
    const std::filesystem::path dir = atlasSetsDir();
    std::vector<std::filesystem::path> sets;
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        if (std::filesystem::exists(entry.path() / "set-rtstruct.dcm"))
            sets.push_back(entry.path());
    std::sort(sets.begin(), sets.end());
    for (const std::filesystem::path& setDir : sets) {
        const std::string setName = setDir.filename().string();
        const ContoursRead read = readContours((setDir / "set-rtstruct.dcm").string());
        const std::map<std::string, double> truth = trueVolumesMm3(setDir / "set-surface-cc.txt");
        std::vector<const Roi*> rois;
        for (const Roi& roi : read.contours.rois)
            if (!roi.slices.empty()) rois.push_back(&roi);
        const std::size_t jobs = defaultJobs(rois.size());
        ocl::WorkerRuntimes runtimes(device, jobs);  // as reconstruct --all opens them
        std::size_t valid = 0, large = 0, beyond = 0, beyondCloserToTruth = 0, withTruth = 0;
        double surfaceErrSum = 0, contourErrSum = 0;
        const double seconds = bestSeconds(1, [&] {
            forEachInOrder(
                rois.size(), jobs,
                [&](std::size_t i, std::size_t worker) {
                    return reconstructSurface(runtimes[worker], *rois[i]).check;
                },
                [&](std::size_t i, const MeshCheckReport& check) {
                    const Roi& roi = *rois[i];
                    valid += check.validSolid();
                    const double contour = contourVolumeMm3(roi);
                    const auto found = truth.find(roi.name);
                    const double trueMm3 = found == truth.end() ? NAN : found->second;
                    if (found != truth.end()) {
                        ++withTruth;
                        surfaceErrSum += std::abs(percentOff(check.volumeMm3, trueMm3));
                        contourErrSum += std::abs(percentOff(contour, trueMm3));
                    }
                    if (contour < kLeastMm3) return;
                    ++large;
                    const double off = percentOff(check.volumeMm3, contour);
                    if (std::abs(off) <= kToleratedPct) return;
                    ++beyond;
                    const bool closer = std::abs(percentOff(check.volumeMm3, trueMm3)) <
                                        std::abs(percentOff(contour, trueMm3));
                    beyondCloserToTruth += closer;
                    std::cout << nlohmann::ordered_json{{"bench", "atlases"},
                                                        {"set", setName},
                                                        {"case", roi.name},
                                                        {"system", "dfrecon"},
                                                        {"planes", roi.slices.size()},
                                                        {"contour_volume_mm3", contour},
                                                        {"volume_vs_contour_pct", off},
                                                        {"volume_vs_truth_pct",
                                                         percentOff(check.volumeMm3, trueMm3)},
                                                        {"contour_vs_truth_pct",
                                                         percentOff(contour, trueMm3)},
                                                        {"closer_to_truth_than_contour", closer},
                                                        {"valid", check.validSolid()}}
                                     .dump()
                              << std::endl;
                });
        });
        const double count = double(std::max<std::size_t>(withTruth, 1));
        std::cout << nlohmann::ordered_json{{"bench", "atlases-summary"},
                                            {"set", setName},
                                            {"system", "dfrecon"},
                                            {"seconds", seconds},
                                            {"rois", rois.size()},
                                            {"valid", valid},
                                            {"rois_at_least_0.5cc", large},
                                            {"beyond_2pct_of_contour_volume", beyond},
                                            {"of_those_closer_to_truth", beyondCloserToTruth},
                                            {"volume_err_mean_abs_pct", surfaceErrSum / count},
                                            {"contour_volume_err_mean_abs_pct",
                                             contourErrSum / count}}
                         .dump()
                  << std::endl;
    }
    return 0;
}

}  // namespace dfrecon::bench
