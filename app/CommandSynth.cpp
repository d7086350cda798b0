// dfrecon synth SHAPE -o OUT.slices: contour slices of an analytic solid.
#include <iostream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "app/Commands.hpp"
#include "app/OutputOptions.hpp"
#include "app/StandardStreams.hpp"
#include "io/contours/SlicesFile.hpp"
#include "io/files/JsonText.hpp"
#include "report/NumberChecks.hpp"
#include "shapes/AnalyticShapes.hpp"

namespace dfrecon::app {

namespace {

struct SynthArgs {
    std::string shape;
    std::string output;
    SynthOptions options;
    double scale = 1.0;
    bool json = false;
};

// Σ |signed area| of outer contours minus holes, times spacing: the
// planimetric volume a planning system would report for these slices.
double planimetricVolume(const Roi& roi, double spacingMm) {
    double volume = 0;
    for (const Slice& slice : roi.slices) volume += netArea(slice.contours) * spacingMm;
    return volume;
}

void runSynth(const SynthArgs& args) {
    const auto shape = makeShape(args.shape, args.scale);
    const ContourSet contours = sliceShape(*shape, args.options);
    const bool toStandardOutput = isStandardStream(args.output);
    if (toStandardOutput && args.json)
        throw std::invalid_argument(
            "-o - and --json would both write to standard output: give one");
    if (toStandardOutput) {
        formatSlices(contours, std::cout);
        if (!std::cout.flush()) throw std::runtime_error("cannot write to standard output");
    } else {
        writeSlicesFile(contours, args.output);
    }

    const Roi& roi = contours.rois.front();
    const double exact = shape->volumeMm3();
    const double estimate = planimetricVolume(roi, args.options.spacingMm);
    if (args.json) {
        nlohmann::ordered_json report = {
            {"command", "synth"},
            {"shape", args.shape},
            {"output", args.output},
            {"spacingMm", args.options.spacingMm},
            {"pointsPerContour", args.options.pointsPerContour},
            {"noiseMm", args.options.noiseMm},
            {"seed", args.options.seed},
            {"scale", args.scale},
            {"slices", roi.slices.size()},
            {"contours", roi.contourCount()},
            {"points", roi.pointCount()},
            {"exactVolumeMm3", exact},
            {"planimetricVolumeMm3", estimate},
        };
        std::cout << jsonText(report, 2) << "\n";
    } else {
        reportStream(toStandardOutput)
            << "wrote " << (toStandardOutput ? "standard output" : args.output) << ": "
            << args.shape << ", " << roi.slices.size() << " slices, " << roi.contourCount()
            << " contours, " << roi.pointCount() << " points\n"
            << "exact volume " << exact / 1000 << " cc; slices' area x spacing " << estimate / 1000
            << " cc\n";
    }
}

}  // namespace

void addSynthCommand(CLI::App& root, const GlobalOptions&) {
    auto args = std::make_shared<SynthArgs>();
    std::string shapes;
    for (const std::string& name : allShapeNames())
        shapes += "\n  " + name + ": " + shapeDescription(name);
    CLI::App* cmd = root.add_subcommand(
        "synth",
        "Write contour slices of an analytic test shape (exact volume and distance known)");
    cmd->footer("Shapes (centred at the origin, lengths at --scale 1):" + shapes +
                "\nSlices sit at cell centres zmin + spacing*(k+1/2).");
    cmd->add_option("shape", args->shape, "Shape name (see below)")
        ->required()
        ->check(CLI::IsMember(allShapeNames()));
    cmd->add_option("-o,--output", args->output, "Output .slices file, or - for standard output")
        ->required();
    cmd->add_option("--spacing", args->options.spacingMm, "Slice spacing in mm")
        ->capture_default_str()
        ->check(kPositive);
    cmd->add_option("--points", args->options.pointsPerContour, "Vertices per contour")
        ->capture_default_str()
        ->check(CLI::Range(3, 1000000));
    cmd->add_option("--noise", args->options.noiseMm,
                    "Std-dev of random vertex displacement in mm (clamped at 3 std-devs)")
        ->capture_default_str()
        ->check(kNonNegative);
    cmd->add_option("--seed", args->options.seed, "Random seed for --noise")->capture_default_str();
    cmd->add_option("--scale", args->scale, "Multiply every length of the shape")
        ->capture_default_str()
        ->check(kPositive);
    cmd->add_flag("--json", args->json, "Print a JSON report instead of text");
    asOutput(cmd->get_option("--output"), OutputKind::File);
    cmd->callback([args] { runSynth(*args); });
}

}  // namespace dfrecon::app
