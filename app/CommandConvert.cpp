// dfrecon convert IN -o OUT: contours from one format to another (.slices,
// DICOM RTSTRUCT), e.g. to take simplified or synthetic contours to a
// planning system, or an RTSTRUCT to the readable .slices text.
#include <filesystem>
#include <iostream>

#include <nlohmann/json.hpp>

#include "app/Commands.hpp"
#include "app/Inputs.hpp"
#include "app/StandardStreams.hpp"
#include "io/RtStruct.hpp"
#include "io/SlicesFile.hpp"

namespace dfrecon::app {

namespace {

struct ConvertArgs {
    std::string input, output, roi, like, label = "dfrecon";
    bool json = false;
};

bool endsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

void runConvert(const ConvertArgs& args, const GlobalOptions& global) {
    const bool toDicom = endsWith(args.output, ".dcm");
    if (!toDicom && !endsWith(args.output, ".slices"))
        throw std::invalid_argument("output '" + args.output + "' needs .slices or .dcm");
    if (!args.like.empty() && !toDicom)
        throw std::invalid_argument("--like applies to DICOM output only");
    const ContourInput input = loadContours(args.input, global);
    ContourSet chosen;
    if (args.roi.empty()) {
        for (const Roi& roi : input.contours.rois)
            if (roi.defect) throw *roi.defect;  // a converted file must hold every ROI
        chosen = input.contours;
    } else
        chosen.rois.push_back(*selectRois(input.contours, args.roi, false).front());

    if (toDicom) {
        RtStructWriteOptions options =
            args.like.empty() ? RtStructWriteOptions{} : referenceFrom(args.like);
        options.structureSetLabel = args.label;
        writeRtStruct(chosen, args.output, options);
    } else {
        for (const Roi& roi : chosen.rois)
            if (!roi.frame.isIdentity())
                throw std::invalid_argument(
                    "ROI '" + roi.name + "' lies in " + roi.frame.orientationName() +
                    " planes (normal " + std::to_string(roi.frame.n.x) + ", " +
                    std::to_string(roi.frame.n.y) + ", " + std::to_string(roi.frame.n.z) +
                    "), and a .slices file holds planes normal to z only; convert it to a "
                    "DICOM RTSTRUCT (.dcm), which holds any orientation");
        writeSlicesFile(chosen, args.output);
    }
    std::size_t contours = 0;
    for (const Roi& roi : chosen.rois) contours += roi.contourCount();
    if (args.json)
        std::cout << nlohmann::ordered_json{{"command", "convert"},
                                            {"input", args.input},
                                            {"inputFormat", input.format},
                                            {"output", args.output},
                                            {"outputFormat",
                                             toDicom ? "DICOM RTSTRUCT" : "dfrecon-slices 1"},
                                            {"rois", chosen.rois.size()},
                                            {"contours", contours}}
                         .dump(2)
                  << "\n";
    else
        std::cout << args.input << ": " << chosen.rois.size() << " ROI(s), " << contours
                  << " contours -> " << args.output << "\n";
}

}  // namespace

void addConvertCommand(CLI::App& root, const GlobalOptions& global) {
    auto args = std::make_shared<ConvertArgs>();
    CLI::App* cmd = root.add_subcommand(
        "convert", "Convert contours between .slices and DICOM RT Structure Sets");
    cmd->footer(
        "The output format follows its extension: .dcm writes an RT Structure Set (closed "
        "planar contours in patient coordinates, DS values of at most 16 characters, exactly "
        "the input's values where they fit), .slices the text format of docs/formats.md. "
        "Without --like the structure set stands alone, with its own study and frame of "
        "reference. Exit codes: 0 done, 1 usage, 2 bad input, 3 runtime failure.");
    cmd->add_option("file", args->input,
                    "Input contours: .slices (- reads it from standard input) or DICOM RTSTRUCT "
                    "(.dcm)")
        ->required();
    cmd->add_option("-o,--output", args->output, "Output file: .dcm or .slices")
        ->required()
        ->check(kNotStandardStream);
    cmd->add_option("--roi", args->roi, "Only this ROI (name or DICOM number; default: all)");
    cmd->add_option("--like", args->like,
                    "A DICOM file (an image of the planning CT, or an RTSTRUCT) whose patient, "
                    "study and frame of reference the output refers to");
    cmd->add_option("--label", args->label, "Structure Set Label of DICOM output")
        ->capture_default_str();
    cmd->add_flag("--json", args->json, "Print a JSON report instead of text");
    cmd->callback([args, &global] { runConvert(*args, global); });
}

}  // namespace dfrecon::app
