// dfrecon-bench structure-set: whole structure sets, every ROI, as
// `dfrecon reconstruct --all` makes them (the surface reconstructed and
// checked as a file holds it), against the route users take today, timed in
// the same run: rasterise each ROI onto a grid of 0.5 mm pixels and the
// planes' spacing, then marching cubes (rasterBaseline in
// recon/MarchingCubesBaselines). Lines per set: dfrecon
// (seconds, valid solids, worst deviation from the contour-implied volume,
// triangles per second, and the reconstruction's stages summed over ROIs)
// and rasterise+mc (seconds, valid solids, the same deviation), each with
// the peak memory of the process that ran that route: every route of every
// case runs in a process of its own (this program again, with --route), as
// a user's command would. The dfrecon line carries the speed ratio. The
// sets: the shared Brodmann atlas, plastimatch's k-means fixture, a head
// CT's BONE alone and with BODY and AIRWAY (build/bench-fixtures/ct_head,
// scripts/ct_structures.py; make bench makes it), and 200 blobs in one ROI.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "baselines/ExternalCommand.hpp"
#include "baselines/MarchingCubesBaselines.hpp"
#include "bench/Benchmarks.hpp"
#include "cl/WorkerRuntimes.hpp"
#include "dfrecon/Contours.hpp"
#include "geometry/MeshCheck.hpp"
#include "geometry/OrderedParallel.hpp"
#include "io/dicom/RtStruct.hpp"
#include "io/labels/MaskContours.hpp"
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
    double peakMemoryMb = 0;          // of the route's own process
    /// dfrecon: the reconstruction's stages summed over ROIs (thread
    /// seconds: the slabs of one ROI run on the cores left free, so they
    /// can add up to more than `seconds`), in ReconstructionStats' order.
    std::vector<std::pair<std::string, double>> phases;
};

// The stages a reconstruction times, by name (ReconstructionStats).
std::vector<std::pair<std::string, double>> phasesOf(const ReconstructionStats& s) {
    return {{"simplify", s.simplifySeconds}, {"fields", s.fieldsSeconds},
            {"medialAxes", s.medialSeconds}, {"triangulation", s.triangulationSeconds},
            {"check", s.checkSeconds},       {"smooth", s.smoothSeconds}};
}

nlohmann::ordered_json toJson(const SetResult& r) {
    return {{"seconds", r.seconds},
            {"rois", r.rois},
            {"valid", r.valid},
            {"triangles", r.triangles},
            {"worstVolumeDeviation", r.worstVolumeDeviation},
            {"within1Pct", r.within1Pct},
            {"peakMemoryMb", r.peakMemoryMb},
            {"phases", r.phases}};
}

SetResult fromJson(const nlohmann::json& j) {
    SetResult r;
    r.seconds = j.at("seconds").get<double>();
    r.rois = j.at("rois").get<std::size_t>();
    r.valid = j.at("valid").get<std::size_t>();
    r.triangles = j.at("triangles").get<std::size_t>();
    r.worstVolumeDeviation = j.at("worstVolumeDeviation").get<double>();
    r.within1Pct = j.at("within1Pct").get<std::size_t>();
    r.peakMemoryMb = j.at("peakMemoryMb").get<double>();
    r.phases = j.at("phases").get<std::vector<std::pair<std::string, double>>>();
    return r;
}

// The process's peak resident memory, in MB (Linux's VmHWM; 0 where /proc
// does not say).
double peakMemoryMb() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // kB
    return 0;
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

// A case: how to read its structure set (not timed), or why it is missing.
struct Case {
    std::string name;
    std::string missing;  // non-empty: skipped, with this reason
    std::function<ContourSet()> load;
};

// An RTSTRUCT file's ROIs named in `rois` (empty: all of them).
Case fileCase(std::string name, const std::filesystem::path& path, std::vector<std::string> rois) {
    Case c{std::move(name), {}, {}};
    if (!std::filesystem::exists(path)) {
        c.missing = path.string() + " not found (make bench makes it)";
        return c;
    }
    c.load = [path, rois] {
        // As users' files are read: runs of planes found (contours/PlaneGaps).
        ContourSet set = readContours(path.string()).contours;
        if (!rois.empty())
            set.rois.erase(std::remove_if(set.rois.begin(), set.rois.end(),
                                          [&](const Roi& roi) {
                                              return std::find(rois.begin(), rois.end(),
                                                               roi.name) == rois.end();
                                          }),
                           set.rois.end());
        return set;
    };
    return c;
}

std::vector<Case> cases() {
    const std::filesystem::path fixtures(DFRECON_FIXTURES);
    const std::filesystem::path head =
        std::filesystem::path(DFRECON_BENCH_FIXTURES) / "ct_head" / "rtstruct.dcm";
    std::vector<Case> all;
    all.push_back(fileCase("brodmann 41 ROIs, 2 mm",
                           std::filesystem::path(DFRECON_SHARED_DATA) / "brodmann-rtstruct.dcm",
                           {}));
    all.push_back(fileCase("kmeans_axial 7 ROIs", fixtures / "kmeans_axial" / "rtstruct.dcm", {}));
    all.push_back(fileCase("head CT bone, 1.5 mm", head, {"BONE"}));
    all.push_back(fileCase("head CT body, airway, bone, 1.5 mm", head, {}));
    // Many contours per plane in one ROI.
    all.push_back({"200 blobs, 240x240x40 voxels of 0.5x0.5x2 mm", {}, [] {
                       return contoursFromLabels(manyBlobLabelVolume(7, 200, 240, 40));
                   }});
    return all;
}

std::vector<const Roi*> roisWithSlices(const ContourSet& set) {
    std::vector<const Roi*> rois;
    for (const Roi& roi : set.rois)
        if (!roi.slices.empty()) rois.push_back(&roi);
    return rois;
}

// dfrecon's route: every ROI reconstructed and checked, as many at a time
// as `dfrecon reconstruct --all` runs them (each worker with its own OpenCL
// queue), timed over the whole set.
SetResult reconstructionRoute(const std::string& device, const ContourSet& set) {
    const std::vector<const Roi*> rois = roisWithSlices(set);
    const std::size_t jobs = defaultJobs(rois.size());
    ocl::WorkerRuntimes runtimes(device, jobs);  // as reconstruct --all opens them
    SetResult r;
    r.seconds = bestSeconds(1, [&] {
        forEachInOrder(
            rois.size(), jobs,
            [&](std::size_t i, std::size_t worker) {
                Reconstruction made = reconstructSurface(runtimes[worker], *rois[i]);
                return std::pair{made.check, made.stats};
            },
            [&](std::size_t i, const std::pair<MeshCheckReport, ReconstructionStats>& made) {
                addRoi(r, made.first, contourVolumeMm3(*rois[i]));
                const auto phases = phasesOf(made.second);
                if (r.phases.empty())
                    r.phases = phases;
                else
                    for (std::size_t p = 0; p < phases.size(); ++p)
                        r.phases[p].second += phases[p].second;
            });
    });
    r.peakMemoryMb = peakMemoryMb();
    return r;
}

// The route users take today, with the same number of workers.
SetResult rasterRoute(const ContourSet& set) {
    const std::vector<const Roi*> rois = roisWithSlices(set);
    std::vector<TriangleSoup> marched(rois.size());
    SetResult r;
    r.seconds = bestSeconds(1, [&] {
        forEachInOrder(
            rois.size(), defaultJobs(rois.size()),
            [&](std::size_t i, std::size_t) { return rasterBaseline(*rois[i], kRasterPixelMm); },
            [&](std::size_t i, TriangleSoup soup) { marched[i] = std::move(soup); });
    });
    // Taken before the checks: the route ends with the marched surfaces, and
    // checking them is ours.
    r.peakMemoryMb = peakMemoryMb();
    for (std::size_t i = 0; i < rois.size(); ++i)
        addRoi(r, checkMesh(marched[i]), contourVolumeMm3(*rois[i]));
    return r;
}

// Runs `dfrecon-bench structure-set --route ROUTE` (this program, started
// afresh, through runCommand) and returns the result it prints. A route's
// process of its own makes its peak memory the route's: in one process a
// case's peak would also hold what earlier cases left on glibc's heap, and
// a fork would inherit OpenCL runtimes whose threads it does not have.
// Throws std::runtime_error when that process fails.
SetResult inOwnProcess(const std::string& device, const std::string& route) {
    std::string name = route;
    std::replace(name.begin(), name.end(), ':', '-');
    const std::filesystem::path log =
        std::filesystem::temp_directory_path() /
        ("dfrecon-bench-" + std::to_string(::getpid()) + "-route-" + name + ".log");
    std::vector<std::string> arguments{"/proc/self/exe", "structure-set", "--route", route};
    if (!device.empty()) arguments.insert(arguments.end(), {"--device", device});
    std::string output;
    try {
        runCommand(arguments, log.string());
        std::ifstream file(log);
        output.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
    } catch (...) {
        std::filesystem::remove(log);
        throw;
    }
    std::filesystem::remove(log);
    try {
        // Its last line: the log holds the route's standard error too.
        const std::size_t last = output.find_last_of('{');
        const std::size_t lineStart =
            last == std::string::npos ? 0 : output.find_last_of('\n', last) + 1;
        return fromJson(nlohmann::json::parse(output.substr(lineStart)));
    } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error("structure-set: route " + route + " printed no result (" +
                                 e.what() + ")");
    }
}

void printLine(const std::string& name, const char* system, const SetResult& r,
               const SetResult* baseline) {
    nlohmann::ordered_json j{{"bench", "structure-set"},
                             {"case", name},
                             {"system", system},
                             {"size", r.rois},
                             {"seconds", r.seconds},
                             {"validSolids", r.valid},
                             {"triangles", r.triangles},
                             {"worstVolumeDeviationPct", 100 * r.worstVolumeDeviation},
                             {"within1Pct", r.within1Pct},
                             {"jobs", defaultJobs(r.rois)},
                             {"peakMemoryMb", r.peakMemoryMb},
                             {"trianglesPerSecond", double(r.triangles) / r.seconds}};
    if (!r.phases.empty()) {
        nlohmann::ordered_json phases;
        for (const auto& [phase, seconds] : r.phases) phases[phase] = seconds;
        j["phaseThreadSeconds"] = phases;
    }
    if (baseline) j["speedupOverBaseline"] = baseline->seconds / r.seconds;
    std::cout << j.dump() << std::endl;
}

}  // namespace

int benchStructureSet(const std::string& device, const std::string& route) {
    const std::vector<Case> all = cases();
    if (!route.empty()) {
        // One route of one case, in this process: CASE:dfrecon or CASE:raster.
        const std::size_t colon = route.find(':');
        const std::string number = route.substr(0, colon);
        const std::string system = colon == std::string::npos ? "" : route.substr(colon + 1);
        const bool digits =
            !number.empty() && number.size() < 4 &&
            std::all_of(number.begin(), number.end(), [](char c) { return c >= '0' && c <= '9'; });
        const std::size_t index = digits ? std::stoul(number) : all.size();
        if (index >= all.size() || !all[index].load || (system != "dfrecon" && system != "raster"))
            throw std::invalid_argument("structure-set --route " + route +
                                        ": expected CASE:dfrecon or CASE:raster with CASE "
                                        "one of the cases that are there, from 0");
        const ContourSet set = all[index].load();
        const SetResult r =
            system == "dfrecon" ? reconstructionRoute(device, set) : rasterRoute(set);
        std::cout << toJson(r).dump() << std::endl;
        return 0;
    }
    for (std::size_t k = 0; k < all.size(); ++k) {
        const Case& c = all[k];
        if (!c.missing.empty()) {
            std::cout << nlohmann::ordered_json{{"bench", "structure-set"},
                                                {"case", c.name},
                                                {"skipped", c.missing}}
                             .dump()
                      << std::endl;
            continue;
        }
        const SetResult ours = inOwnProcess(device, std::to_string(k) + ":dfrecon");
        const SetResult baseline = inOwnProcess(device, std::to_string(k) + ":raster");
        printLine(c.name, "dfrecon", ours, &baseline);
        printLine(c.name, "rasterise+mc", baseline, nullptr);
    }
    return 0;
}

}  // namespace dfrecon::bench
