// dfrecon histogram IN --roi OAR --to TARGET: the overlap-volume histogram
// and the distance-to-target histogram of an organ at risk against a
// target (dfrecon/Algebra, algebra/DistanceHistograms), as CSV, JSON and a
// PNG plot.
#include <cmath>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "app/Commands.hpp"
#include "app/Inputs.hpp"
#include "app/OutputOptions.hpp"
#include "app/Progress.hpp"
#include "app/StandardStreams.hpp"
#include "dfrecon/Algebra.hpp"
#include "io/files/AtomicWrite.hpp"
#include "io/files/JsonText.hpp"
#include "io/images/LinePlot.hpp"
#include "report/Reports.hpp"

namespace dfrecon::app {

namespace {

struct HistogramArgs {
    std::string input, oar, target, csv, plot;
    double binMm = 0.5, volumeStepMm = 0.5, surfaceSpacingMm = 0.5;
    bool json = false, reference = false;
};

void runHistogram(const HistogramArgs& args, const GlobalOptions& global) {
    if (!(args.binMm > 0) || !(args.volumeStepMm > 0) || !(args.surfaceSpacingMm > 0))
        throw std::invalid_argument("--bin, --step and --surface-spacing must be > 0 mm");
    const ContourInput input = loadContours(args.input, global, {args.oar, args.target});
    const Roi& oar = *selectRois(input.contours, args.oar, false).front();
    const Roi& target = *selectRois(input.contours, args.target, false).front();
    ocl::Runtime runtime(global.device);
    DistanceHistogramOptions options;
    options.volumeStepMm = args.volumeStepMm;
    options.surfaceSpacingMm = args.surfaceSpacingMm;
    options.backend = args.reference ? DistanceBackend::Reference : DistanceBackend::Device;
    DistanceHistograms h;
    {
        Progress progress("histogram of " + oar.name, !global.quiet);
        progress.update(0);
        options.progress = [&progress](double fraction) { progress.update(fraction); };
        h = roiDistanceHistograms(runtime, input.contours, oar.name, target.name, {}, options);
        options.progress = nullptr;
    }
    // Rows every --bin mm from below the nearest sample to past the farthest.
    const double lo =
        std::floor(std::min(h.volume.minMm(), h.surface.minMm()) / args.binMm) * args.binMm;
    const double hi =
        std::ceil(std::max(h.volume.maxMm(), h.surface.maxMm()) / args.binMm) * args.binMm;
    if ((hi - lo) / args.binMm > 1e6)
        throw std::invalid_argument("--bin " + std::to_string(args.binMm) +
                                    " mm gives more than a million rows");
    std::vector<double> distance, volumeFraction, surfaceFraction;
    for (double d = lo; d <= hi + 1e-9 * args.binMm; d += args.binMm) {
        distance.push_back(d);
        volumeFraction.push_back(h.volume.fractionWithin(d));
        surfaceFraction.push_back(h.surface.fractionWithin(d));
    }
    if (!args.csv.empty()) {
        writeStreamAtomically(args.csv, [&](std::ostream& csv) {
            csv << "distance_mm,overlap_volume_fraction,overlap_volume_cc,surface_fraction\n";
            csv.precision(10);
            for (std::size_t k = 0; k < distance.size(); ++k)
                csv << distance[k] << "," << volumeFraction[k] << ","
                    << volumeFraction[k] * h.volume.total / kCubicMmPerCc << ","
                    << surfaceFraction[k] << "\n";
        });
    }
    if (!args.plot.empty()) {
        LinePlot plot;
        plot.title = oar.name + " around " + target.name;
        plot.xLabel = "signed distance to " + target.name + " (mm, < 0 inside)";
        plot.yLabel = "fraction within";
        plot.curves.push_back({"overlap volume (OVH)", {0, 96, 255}, distance, volumeFraction});
        plot.curves.push_back({"surface (DTH)", {255, 128, 0}, distance, surfaceFraction});
        writeLinePlotPng(args.plot, plot);
    }
    const auto summary = [](const WeightedDistances& w) {
        return nlohmann::ordered_json{{"minMm", w.minMm()},
                                      {"meanMm", w.meanMm()},
                                      {"maxMm", w.maxMm()},
                                      {"fractionInsideTarget", w.fractionWithin(-1e-300)},
                                      {"samples", w.distanceMm.size()}};
    };
    if (args.json) {
        nlohmann::ordered_json rows = nlohmann::ordered_json::array();
        for (std::size_t k = 0; k < distance.size(); ++k)
            rows.push_back({distance[k], volumeFraction[k], surfaceFraction[k]});
        nlohmann::ordered_json report{
            {"command", "histogram"},
            {"input", args.input},
            {"oar", oar.name},
            {"target", target.name},
            {"solid", "reconstructed surface"},
            {"oarVolumeCc", h.oarVolumeMm3 / kCubicMmPerCc},
            {"sampledVolumeCc", h.volume.total / kCubicMmPerCc},
            {"volumeStepMm", h.volumeStepMm},
            {"surfaceSpacingMm", h.surfaceSpacingMm},
            {"oarAreaCm2", h.oarAreaMm2 / 100},
            {"volume", summary(h.volume)},
            {"surface", summary(h.surface)},
            {"binMm", args.binMm},
            {"columns", {"distanceMm", "overlapVolumeFraction", "surfaceFraction"}},
            {"rows", rows}};
        std::cout << jsonText(report, 2) << "\n";
    } else {
        std::cout << oar.name << " around " << target.name << ": volume "
                  << h.oarVolumeMm3 / kCubicMmPerCc << " cc, "
                  << 100 * h.volume.fractionWithin(-1e-300) << " % inside the target, nearest "
                  << h.volume.minMm() << " mm, mean " << h.volume.meanMm() << " mm, farthest "
                  << h.volume.maxMm() << " mm";
        if (!args.csv.empty()) std::cout << " -> " << args.csv;
        if (!args.plot.empty()) std::cout << " -> " << args.plot;
        std::cout << "\n";
    }
}

}  // namespace

void addHistogramCommand(CLI::App& root, const GlobalOptions& global) {
    auto args = std::make_shared<HistogramArgs>();
    CLI::App* cmd = root.add_subcommand(
        "histogram", "Overlap-volume and distance-to-target histograms of an OAR against a target");
    cmd->footer(
        "The overlap-volume histogram (OVH) gives, for each distance d, the fraction of the "
        "OAR's volume within d of the target (signed: d < 0 inside the target); the "
        "distance-to-target histogram (DTH) the same fraction of the OAR's surface area. Both "
        "ROIs are their reconstructed surfaces; distances are exact (closest triangle, signed "
        "by pseudo-normals), the volume integrated over cubic cells of --step, the surface over "
        "cells no wider than --surface-spacing. Example: dfrecon histogram plan.dcm --roi "
        "Rectum --to PTV -o rectum-ovh.csv --plot rectum-ovh.png. Exit codes: 0 done, 1 usage, 2 "
        "bad input, 3 runtime failure.");
    cmd->add_option("file", args->input, contourInputHelp())->required();
    cmd->add_option("--roi", args->oar, "The organ at risk (name or DICOM number)")->required();
    cmd->add_option("--to", args->target, "The target (name or DICOM number)")->required();
    cmd->add_option("-o,--csv", args->csv,
                    "Write the table here: distance_mm, overlap_volume_fraction, "
                    "overlap_volume_cc, surface_fraction (cumulative, one row per --bin)")
        ->check(kNotStandardStream);
    cmd->add_option("--plot", args->plot, "Write both curves as a PNG plot")
        ->check(kNotStandardStream);
    cmd->add_option("--bin", args->binMm, "Row spacing of the table (mm)")->capture_default_str();
    cmd->add_option(
           "--step", args->volumeStepMm,
           "Edge of the cubic cells the OAR's volume is integrated over (mm; grows for very "
           "large OARs, reported as volumeStepMm)")
        ->capture_default_str();
    cmd->add_option("--surface-spacing", args->surfaceSpacingMm,
                    "Largest distance from a surface cell's sample to its points (mm; grows "
                    "where it would take more than 4 194 304 cells, reported as "
                    "surfaceSpacingMm)")
        ->capture_default_str();
    cmd->add_flag("--reference", args->reference,
                  "Compute distances with the C++ reference instead of the OpenCL kernel");
    cmd->add_flag("--json", args->json, "Print a JSON report (summary and every row)");
    asOutput(cmd->get_option("--csv"), OutputKind::File);
    asOutput(cmd->get_option("--plot"), OutputKind::File);
    cmd->callback([args, &global] { runHistogram(*args, global); });
}

}  // namespace dfrecon::app
