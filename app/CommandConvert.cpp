// dfrecon convert IN -o OUT: contours from one format to another (.slices,
// DICOM RTSTRUCT), e.g. to take simplified or synthetic contours to a
// planning system, or an RTSTRUCT to the readable .slices text.
#include <filesystem>
#include <iostream>
#include <optional>

#include <nlohmann/json.hpp>

#include "app/Commands.hpp"
#include "app/Inputs.hpp"
#include "app/OutputOptions.hpp"
#include "app/StandardStreams.hpp"
#include "io/contours/SlicesFile.hpp"
#include "io/dicom/RtStruct.hpp"
#include "io/files/FileNames.hpp"
#include "io/files/JsonText.hpp"

namespace dfrecon::app {

namespace {

struct ConvertArgs {
    std::string input, output, roi, like, label = "dfrecon", roiType = "ORGAN";
    bool json = false;
    bool roiTypeGiven = false;
};

void runConvert(const ConvertArgs& args, const GlobalOptions& global) {
    const bool toDicom = endsWithIgnoringCase(args.output, ".dcm");
    if (!toDicom && !endsWithIgnoringCase(args.output, ".slices"))
        throw std::invalid_argument("output '" + args.output + "' needs .slices or .dcm");
    if (!args.like.empty() && !toDicom)
        throw std::invalid_argument("--like applies to DICOM output only");
    if (!toDicom && args.roiTypeGiven)
        throw std::invalid_argument("--roi-type applies to DICOM output only");
    const ContourInput input = loadContours(args.input, global, onlyRoi(args.roi));
    ContourSet chosen;
    if (args.roi.empty()) {
        for (const Roi& roi : input.contours.rois)
            if (roi.defect) throw *roi.defect;  // a converted file must hold every ROI
        chosen = input.contours;
    } else
        chosen.rois.push_back(*selectRois(input.contours, args.roi, false).front());

    RtStructWriteSummary written;
    std::optional<DicomImageSeries> series;
    std::string likeFrame;
    if (toDicom) {
        RtStructWriteOptions options =
            args.like.empty() ? RtStructWriteOptions{} : referenceFrom(args.like);
        options.structureSetLabel = args.label;
        options.defaultRoiType = args.roiType;
        written = writeRtStruct(chosen, args.output, options);
        series = std::move(options.imageSeries);
        likeFrame = options.frameOfReferenceUid;
        if (!global.quiet) {
            if (series)
                for (const std::string& skipped : series->skipped)
                    std::cerr << "warning: --like " << args.like << ": skipped " << skipped << "\n";
            for (const std::string& warning : written.warnings)
                std::cerr << "warning: " << args.output << ": " << warning << "\n";
        }
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
    if (args.json) {
        nlohmann::ordered_json report{
            {"command", "convert"},
            {"input", args.input},
            {"inputFormat", contourFormatName(input.format)},
            {"output", args.output},
            {"outputFormat", toDicom ? "DICOM RTSTRUCT" : "dfrecon-slices 1"},
            {"rois", chosen.rois.size()},
            {"contours", contours}};
        if (!args.like.empty()) {
            nlohmann::ordered_json like{{"path", args.like}, {"frameOfReferenceUid", likeFrame}};
            if (series) {
                like["seriesInstanceUid"] = series->seriesInstanceUid;
                like["modality"] = series->modality;
                like["images"] = series->images.size();
                like["filesSkipped"] = series->skipped.size();
                like["contoursOnImages"] = written.contoursOnImages;
                like["contoursOffImages"] = written.contoursOffImages;
            }
            report["like"] = like;
        }
        report["warnings"] = written.warnings;
        std::cout << jsonText(report, 2) << "\n";
    } else {
        std::cout << args.input << ": " << chosen.rois.size() << " ROI(s), " << contours
                  << " contours -> " << args.output;
        if (series)
            std::cout << " (series " << series->seriesInstanceUid << ", " << series->images.size()
                      << " images; " << written.contoursOnImages << " contours on an image, "
                      << written.contoursOffImages << " on none)";
        std::cout << "\n";
    }
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
        "reference. With --like a CT (a folder of its images, or one image of it, which stands "
        "for the images of its folder with its Series Instance UID) the structure set lists every "
        "image of the series and each contour refers to the image whose plane holds it (within "
        "0.01 mm); contours in no image plane, and ROIs at an angle to the images, refer to none "
        "and are counted in a warning. ROIs keep their display colour and RT ROI Interpreted "
        "Type; those without get a fixed palette of 12 colours in turn and --roi-type. Exit "
        "codes: 0 done, 1 usage, 2 bad input (also an unreadable --like series), 3 runtime "
        "failure.");
    cmd->add_option("file", args->input, contourInputHelp())->required();
    cmd->add_option("-o,--output", args->output, "Output file: .dcm or .slices")
        ->required()
        ->check(kNotStandardStream);
    cmd->add_option("--roi", args->roi, "Only this ROI (name or DICOM number; default: all)");
    cmd->add_option("--like", args->like,
                    "The planning CT the output refers to: a folder of its images or one of them "
                    "(patient, study, frame of reference, and every image of the series), or an "
                    "RTSTRUCT (patient, study and frame of reference only)");
    std::vector<std::string> roiTypes(kRoiInterpretedTypes.begin(), kRoiInterpretedTypes.end());
    CLI::Option* roiType =
        cmd->add_option("--roi-type", args->roiType,
                        "RT ROI Interpreted Type of ROIs that have none (an RTSTRUCT input's own "
                        "types are kept): one of the DICOM defined terms")
            ->check(CLI::IsMember(roiTypes))
            ->capture_default_str();
    cmd->add_option("--label", args->label, "Structure Set Label of DICOM output")
        ->capture_default_str();
    cmd->add_flag("--json", args->json, "Print a JSON report instead of text");
    asOutput(cmd->get_option("--output"), OutputKind::File);
    cmd->callback([args, &global, roiType] {
        args->roiTypeGiven = roiType->count() > 0;
        runConvert(*args, global);
    });
}

}  // namespace dfrecon::app
