// Reconstruction against known truth on real anatomy (issue 34): smoothed
// atlas-label surfaces cut by planes (scripts/truth_sets.sh; axial, coronal
// and sagittal, 1.5–5 mm, off the voxel grid), every ROI reconstructed by
// every system and measured against the surface that was cut:
//   contour-implied   Σ plane area × plane spacing (what planning systems count; volume only)
//   levin-mc          shape-based interpolation: exact 2D fields linear in z, marching cubes 0.5 mm
//   raster-mc         each plane filled on 0.5 mm pixels, stacked, marching cubes
//   dfrecon-linear    --interpolation linear
//   dfrecon-smooth    --interpolation smooth
// ("default": true marks the dfrecon row whose options are the defaults).
// Distances are sampled uniformly by area on both surfaces (kSamples each)
// and split by where they lie: near a plane (t < 0.25 or t > 0.75 of the
// slab), mid-slab, or beyond the end planes (caps). Volumes are split the
// same way: between the end planes and beyond them (geometry/SurfaceMeasures).
// The sets are read as users' files are (api readContours): an ROI with
// planes left empty (a sagittal set's two hemispheres) is one piece per run
// of planes for every system, the baselines included, and the gap between
// runs is no slab (contours/PlaneGaps).
// One JSON line per ROI and system, then one `truth-summary` line per set
// and system with the targets.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <numeric>

#include <nlohmann/json.hpp>

#include "baselines/MarchingCubesBaselines.hpp"
#include "bench/Benchmarks.hpp"
#include "bench/SlabErrors.hpp"
#include "contours/PlaneGaps.hpp"
#include "dfrecon/Contours.hpp"
#include "geometry/MeshCheck.hpp"
#include "geometry/SurfaceMeasures.hpp"
#include "geometry/TriangleBvh.hpp"
#include "io/mesh/MeshIO.hpp"
#include "recon/Reconstruction.hpp"
#include "simplify/SimplificationVerifier.hpp"

namespace dfrecon::bench {

namespace {

constexpr std::size_t kSamples = 20000;
constexpr double kBaselineVoxelMm = 0.5;

struct Case {
    std::string set, name;
    TriangleSoup truth;  // in the ROI's plane frame
    double truthVolumeMm3 = 0, truthBetweenMm3 = 0;
    std::vector<std::vector<double>> runsMm;  // each run's planes (contours/PlaneGaps)
    std::size_t planes = 0;
    std::vector<Vec3> truthSamples;
    TriangleBvh* truthBvh = nullptr;
};

struct Row {
    std::string system;
    bool isDefault = false, valid = false;
    double seconds = 0, volumeErrPct = 0, betweenErrPct = 0, capsErrPct = 0;
    std::size_t triangles = 0;
    SlabErrors split;
    ErrorStats caps;
};

/// The volume of `soup` between the end planes of each run.
double volumeBetweenPlanes(const TriangleSoup& soup,
                           const std::vector<std::vector<double>>& runsMm) {
    double volume = 0;
    for (const std::vector<double>& planesMm : runsMm)
        volume +=
            volumeBelowPlane(soup, planesMm.back()) - volumeBelowPlane(soup, planesMm.front());
    return volume;
}

/// Each run of `roi`'s planes reconstructed by `baseline` on its own, as
/// reconstructSurface does for dfrecon: no baseline bridges a gap.
TriangleSoup perRun(const Roi& roi, const std::function<TriangleSoup(const Roi&)>& baseline) {
    TriangleSoup all;
    for (const Roi& run : planeRuns(roi)) appendSoup(all, baseline(run));
    return all;
}

Row measure(const Case& c, const std::string& system, double seconds, const TriangleSoup& soup) {
    Row row;
    row.system = system;
    row.seconds = seconds;
    const MeshCheckReport check = checkMesh(soup);
    row.valid = check.validSolid();
    row.triangles = check.triangles;
    row.volumeErrPct = 100 * (check.volumeMm3 / c.truthVolumeMm3 - 1);
    const double between = volumeBetweenPlanes(soup, c.runsMm);
    // Both parts as a share of the true total, so they add up to the whole error.
    row.betweenErrPct = 100 * (between - c.truthBetweenMm3) / c.truthVolumeMm3;
    row.capsErrPct = row.volumeErrPct - row.betweenErrPct;
    std::vector<ErrorSample> errors;
    const TriangleBvh bvh(soup);
    for (const Vec3& p : sampleTriangles(soup, kSamples, 7))
        errors.push_back({p.z, c.truthBvh->nearest(p).distance});
    for (const Vec3& p : c.truthSamples) errors.push_back({p.z, bvh.nearest(p).distance});
    row.split = splitBySlabPosition(errors, c.runsMm);
    std::vector<ErrorSample> beyond;
    for (const ErrorSample& e : errors)
        if (beyondEveryRun(e.zMm, c.runsMm)) beyond.push_back(e);
    // The caps' samples as one "slab" spanning everything (planes ±inf).
    row.caps = splitBySlabPosition(beyond, {-1e300, 1e300}).slab;
    return row;
}

void printRow(const Case& c, const Row& r, double volumeErrPctOnly = NAN) {
    nlohmann::ordered_json j{
        {"bench", "truth"}, {"set", c.set}, {"case", c.name}, {"system", r.system}};
    if (!std::isnan(volumeErrPctOnly)) {
        j["volume_err_pct"] = volumeErrPctOnly;
        std::cout << j.dump() << std::endl;
        return;
    }
    j["default"] = r.isDefault;
    j["seconds"] = r.seconds;
    j["triangles"] = r.triangles;
    j["valid"] = r.valid;
    j["planes"] = c.planes;
    j["volume_err_pct"] = r.volumeErrPct;
    j["between_planes_volume_err_pct"] = r.betweenErrPct;
    j["caps_volume_err_pct"] = r.capsErrPct;
    j["slab_mean_mm"] = orNull(r.split.slab, &ErrorStats::meanMm);
    j["slab_p95_mm"] = orNull(r.split.slab, &ErrorStats::p95Mm);
    j["slab_max_mm"] = orNull(r.split.slab, &ErrorStats::maxMm);
    j["near_plane_mean_mm"] = orNull(r.split.nearPlane, &ErrorStats::meanMm);
    j["mid_slab_mean_mm"] = orNull(r.split.midSlab, &ErrorStats::meanMm);
    j["mid_slab_p95_mm"] = orNull(r.split.midSlab, &ErrorStats::p95Mm);
    j["caps_mean_mm"] = orNull(r.caps, &ErrorStats::meanMm);
    j["caps_p95_mm"] = orNull(r.caps, &ErrorStats::p95Mm);
    std::cout << j.dump() << std::endl;
}

double median(std::vector<double> v) {
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double meanAbs(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += std::abs(x);
    return v.empty() ? NAN : s / double(v.size());
}

/// The folder of truth sets: made by scripts/truth_sets.sh when missing.
std::filesystem::path truthSetsDir(const std::string& requested) {
    const std::filesystem::path dir = requested.empty()
                                          ? std::filesystem::path(DFRECON_BUILD_DIR) / "truth-sets"
                                          : std::filesystem::path(requested);
    const std::string command = std::string("bash '") + DFRECON_SOURCE_DIR +
                                "/scripts/truth_sets.sh' '" + dir.string() + "'";
    if (std::system(command.c_str()) != 0)
        throw std::runtime_error("truth: " + command + " failed");
    return dir;
}

}  // namespace

int benchTruth(const std::string& device, const std::string& setsDir, const std::string& onlySet) {
    ocl::Runtime runtime(device);
    const std::filesystem::path dir = truthSetsDir(setsDir);
    std::vector<std::filesystem::path> sets;
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        if (std::filesystem::exists(entry.path() / "set-rtstruct.dcm") &&
            (onlySet.empty() || entry.path().filename() == onlySet))
            sets.push_back(entry.path());
    std::sort(sets.begin(), sets.end());
    const ReconstructionOptions defaults;
    for (const std::filesystem::path& setDir : sets) {
        const std::string setName = setDir.filename().string();
        const ContoursRead load = readContours((setDir / "set-rtstruct.dcm").string());
        // Per system: each ROI's volume error and slab mean, for the summary.
        std::map<std::string, std::vector<double>> volumeErr, slabMean, triangles;
        std::map<std::string, std::size_t> validCount;
        std::map<std::string, double> secondsSum;
        std::vector<double> levinSlab;
        std::map<std::string, std::size_t> beatsLevin;  // slab mean ≤ 0.6 × levin-mc's
        for (const Roi& roi : load.contours.rois) {
            const std::filesystem::path plyPath = setDir / (roi.name + ".ply");
            if (!std::filesystem::exists(plyPath) || roi.slices.size() < 2) continue;
            Case c{setName, roi.name, readTriangleSoup(plyPath.string()), 0, 0, {}, {}, {}};
            for (Vec3& p : c.truth.points) p = roi.frame.fromPatient(p);
            for (const Roi& run : planeRuns(roi)) {
                c.runsMm.emplace_back();
                for (const Slice& s : run.slices)
                    if (!s.contours.empty()) c.runsMm.back().push_back(s.zMm);
                c.planes += c.runsMm.back().size();
            }
            // The atlas's own axes may be mirrored (a NIfTI sform with a
            // negative determinant), which turns the true surface inside out.
            if (measureSurface(c.truth).volumeMm3 < 0)
                for (auto& t : c.truth.triangles) std::swap(t[1], t[2]);
            c.truthVolumeMm3 = measureSurface(c.truth).volumeMm3;
            c.truthBetweenMm3 = volumeBetweenPlanes(c.truth, c.runsMm);
            c.truthSamples = sampleTriangles(c.truth, kSamples, 11);
            TriangleBvh truthBvh(c.truth);
            c.truthBvh = &truthBvh;

            const double implied = 100 * (contourVolumeMm3(roi) / c.truthVolumeMm3 - 1);
            Row impliedRow;
            impliedRow.system = "contour-implied";
            printRow(c, impliedRow, implied);
            volumeErr["contour-implied"].push_back(implied);

            std::vector<Row> rows;
            TriangleSoup soup;
            double seconds = bestSeconds(1, [&] {
                soup = perRun(roi, [&](const Roi& run) {
                    const SliceFields fields = computeSliceFields(
                        runtime, run.slices, gridForSlices(run.slices, kBaselineVoxelMm));
                    return toTriangleSoup(levinBaseline(fields));
                });
            });
            rows.push_back(measure(c, "levin-mc", seconds, soup));
            seconds = bestSeconds(1, [&] {
                soup = perRun(roi,
                              [](const Roi& run) { return rasterBaseline(run, kBaselineVoxelMm); });
            });
            rows.push_back(measure(c, "raster-mc", seconds, soup));
            for (Interpolation mode : {Interpolation::Linear, Interpolation::Smooth}) {
                ReconstructionOptions options;
                options.interpolation = mode;
                Reconstruction result;
                seconds =
                    bestSeconds(1, [&] { result = reconstructSurface(runtime, roi, options); });
                Row row =
                    measure(c, mode == Interpolation::Linear ? "dfrecon-linear" : "dfrecon-smooth",
                            seconds, result.surface);
                row.isDefault = mode == defaults.interpolation;
                rows.push_back(row);
            }
            for (const Row& r : rows) {
                printRow(c, r);
                volumeErr[r.system].push_back(r.volumeErrPct);
                slabMean[r.system].push_back(r.split.slab.meanMm);
                triangles[r.system].push_back(double(r.triangles));
                validCount[r.system] += r.valid;
                secondsSum[r.system] += r.seconds;
            }
            const double levin = rows[0].split.slab.meanMm;
            for (const Row& r : rows) beatsLevin[r.system] += r.split.slab.meanMm <= 0.6 * levin;
        }
        for (const auto& [system, errors] : volumeErr) {
            nlohmann::ordered_json j{{"bench", "truth-summary"},
                                     {"set", setName},
                                     {"system", system},
                                     {"rois", errors.size()},
                                     {"volume_err_median_pct", median(errors)},
                                     {"volume_err_mean_abs_pct", meanAbs(errors)}};
            if (slabMean.count(system)) {
                const std::vector<double>& slab = slabMean[system];
                j["valid"] = validCount[system];
                j["slab_mean_median_mm"] = median(slab);
                j["slab_mean_mean_mm"] =
                    std::accumulate(slab.begin(), slab.end(), 0.0) / double(slab.size());
                j["rois_within_0.6_levin"] = beatsLevin[system];
                const auto& t = triangles[system];
                j["triangles_vs_levin"] = std::accumulate(t.begin(), t.end(), 0.0) /
                                          std::accumulate(triangles["levin-mc"].begin(),
                                                          triangles["levin-mc"].end(), 0.0);
                j["seconds"] = secondsSum[system];
            }
            std::cout << j.dump() << std::endl;
        }
    }
    return 0;
}

}  // namespace dfrecon::bench
