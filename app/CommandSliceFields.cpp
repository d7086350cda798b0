// dfrecon fields IN.slices -o DIR: each slice's exact 2D signed distance
// field and nearest-primitive ids (docs/fields.md), as NRRD volumes and,
// with --png, pictures.
#include <cstdio>
#include <filesystem>
#include <iostream>

#include <nlohmann/json.hpp>

#include "api/Stopwatch.hpp"
#include "app/Commands.hpp"
#include "app/Inputs.hpp"
#include "app/OutputOptions.hpp"
#include "app/Progress.hpp"
#include "app/StandardStreams.hpp"
#include "dfrecon/Field.hpp"
#include "io/files/AtomicWrite.hpp"
#include "io/files/JsonText.hpp"
#include "io/images/FieldImages.hpp"
#include "io/volumes/RawVolume.hpp"
#include "recon/MedialAxis.hpp"
#include "report/NumberChecks.hpp"
#include "report/Reports.hpp"

namespace dfrecon::app {

namespace {

struct FieldsArgs {
    std::string input, outputDir, roi;
    bool all = false, png = false, json = false;
    double pixelMm = 0;
    double isoStepMm = 5;
    double contourErrorMm = 0;
};

// The ROI's slices with every contour simplified to within `epsilonMm`
// (recon/ContourSimplification); the report gets point counts and the
// largest edge deviation.
nlohmann::ordered_json writeRoiFields(const Roi& roi, const std::string& fileStem,
                                      const std::vector<Slice>& slices, const SliceFields& fields,
                                      const FieldsArgs& args, const GlobalOptions& global) {
    namespace fs = std::filesystem;
    const std::string stem = (fs::path(args.outputDir) / fileStem).string();
    const SliceGrid& grid = fields.grid;
    const SpacingStats spacing = spacingOf(roi);

    // Sample (i, j) of slice s is centred at plane point originMm + (i + ½,
    // j + ½)·pixelMm at the slice's z; the frame places it in patient LPS.
    const PlaneFrame& frame = roi.frame;
    auto patientOrigin = [&](double zMm) {
        return frame.toPatient(
            {grid.originMm.x + 0.5 * grid.pixelMm, grid.originMm.y + 0.5 * grid.pixelMm, zMm});
    };
    RawVolumeInfo info;
    info.width = grid.width;
    info.height = grid.height;
    info.slices = int(fields.sliceCount());
    info.originMm = patientOrigin(fields.zMm.front());
    info.stepMm = {grid.pixelMm * frame.u, grid.pixelMm * frame.v,
                   (spacing.meanMm > 0 ? spacing.meanMm : 1.0) * frame.n};
    if (!spacing.uniform)
        for (double zMm : fields.zMm) info.sliceOriginsMm.push_back(patientOrigin(zMm));
    nlohmann::ordered_json files = nlohmann::ordered_json::array();
    info.description = "dfrecon signed distance (mm, negative inside) of ROI " + roi.name;
    for (const std::string& header :
         writeRawVolume(stem + "-distance.nhdr", stem + "-distance.raw", fields.distanceMm, info))
        files.push_back(header);
    files.push_back(stem + "-distance.raw");
    info.description = "dfrecon nearest-primitive ids of ROI " + roi.name + " (docs/fields.md)";
    for (const std::string& header :
         writeRawVolume(stem + "-ids.nhdr", stem + "-ids.raw", fields.nearestId, info))
        files.push_back(header);
    files.push_back(stem + "-ids.raw");
    if (!spacing.uniform && !global.quiet)
        std::cerr << "dfrecon: warning: ROI '" << roi.name << "': planes are unevenly spaced ("
                  << spacing.minMm << " to " << spacing.maxMm
                  << " mm), which one NRRD volume cannot hold; wrote one 2D header per slice ("
                  << fileStem << "-distance-NNN.nhdr, " << fileStem << "-ids-NNN.nhdr)\n";

    if (args.png) {
        Progress progress("pictures of " + roi.name, !global.quiet);
        const ImageFrame image{grid.originMm, grid.pixelMm, grid.width, grid.height};
        for (std::size_t s = 0; s < fields.sliceCount(); ++s) {
            char suffix[32];
            std::snprintf(suffix, sizeof suffix, "-%03zu.png", s);
            const std::size_t offset = s * grid.pixelCount();
            writeSignedFieldPng(stem + "-distance" + suffix, fields.distanceMm.data() + offset,
                                image, slices[s].contours, args.isoStepMm);
            writeLabelPng(stem + "-ids" + suffix, fields.nearestId.data() + offset, image,
                          slices[s].contours);
            files.push_back(stem + "-distance" + suffix);
            files.push_back(stem + "-ids" + suffix);
            if (s + 1 < fields.sliceCount()) {
                // The sum with the next slice and its sign border: the medial
                // axes the reconstruction walks (paper Fig. 4).
                const SliceSum sum = sumSlices(fields, s, s + 1);
                std::vector<PixelMark> medial;
                for (const MedialAxis& axis : traceMedialAxes(fields, s, s + 1, sum))
                    for (const MedialPixel& p : axis.pixels) medial.push_back({p.i, p.j});
                std::vector<Polygon> both = slices[s].contours;
                both.insert(both.end(), slices[s + 1].contours.begin(),
                            slices[s + 1].contours.end());
                writeSignedFieldPng(stem + "-medial" + suffix, sum.sumMm.data(), image, both,
                                    args.isoStepMm, medial);
                files.push_back(stem + "-medial" + suffix);
            }
            progress.update(double(s + 1) / double(fields.sliceCount()));
        }
    }

    nlohmann::ordered_json sliceList = nlohmann::ordered_json::array();
    for (std::size_t s = 0; s < fields.sliceCount(); ++s)
        sliceList.push_back({{"index", s},
                             {"zMm", fields.zMm[s]},
                             {"firstSampleLpsMm", xyzJson(patientOrigin(fields.zMm[s]))},
                             {"contours", slices[s].contours.size()}});
    const nlohmann::ordered_json meta = {
        {"roi", roi.name},
        {"grid",
         {{"originMm", {grid.originMm.x, grid.originMm.y}},
          {"pixelMm", grid.pixelMm},
          {"width", grid.width},
          {"height", grid.height},
          {"pixelCentre", "originMm + (i + 0.5, j + 0.5) * pixelMm, in plane coordinates"}}},
        {"planeFrame",
         {{"u", xyzJson(frame.u)},
          {"v", xyzJson(frame.v)},
          {"n", xyzJson(frame.n)},
          {"toPatient", "LPS = x * u + y * v + zMm * n"}}},
        {"layout", "slice-major, then rows (j), then columns (i); little-endian"},
        {"distance",
         {{"file", fs::path(stem + "-distance.raw").filename().string()},
          {"type", "float32"},
          {"units", "mm"},
          {"sign", "negative inside"}}},
        {"ids",
         {{"file", fs::path(stem + "-ids.raw").filename().string()},
          {"type", "uint32"},
          {"encoding",
           "bit 0: vertex(1)/segment(0); bits 1-19: index in contour; bits 20-31: "
           "contour index in slice; 0xffffffff: none"}}},
        {"slices", sliceList}};
    writeStreamAtomically(stem + "-fields.json",
                          [&](std::ostream& out) { out << jsonText(meta, 2) << "\n"; });
    files.push_back(stem + "-fields.json");
    return files;
}

void runFields(const FieldsArgs& args, const GlobalOptions& global) {
    Stopwatch watch;
    const ContourInput load = loadContours(args.input, global, onlyRoi(args.roi));
    const std::vector<const Roi*> rois = selectRois(load.contours, args.roi, args.all);
    const double loadSeconds = watch.lap();
    std::filesystem::create_directories(args.outputDir);

    ocl::Runtime runtime(global.device);
    nlohmann::ordered_json reports = nlohmann::ordered_json::array();
    const std::vector<std::string> stems = uniqueFileStems(rois);
    for (std::size_t r = 0; r < rois.size(); ++r) {
        const Roi* roi = rois[r];
        if (roi->defect) throw *roi->defect;
        if (roi->slices.empty())
            throw std::invalid_argument("ROI '" + roi->name + "' has no slices");
        watch.restartLap();
        ContourSimplificationSummary simplified;
        const std::vector<Slice> slices = fieldPlanes(*roi, args.contourErrorMm, &simplified);
        const nlohmann::ordered_json simplification =
            args.contourErrorMm > 0
                ? nlohmann::ordered_json{{"contourErrorMm", simplified.contourErrorMm},
                                         {"pointsBefore", simplified.pointsBefore},
                                         {"pointsAfter", simplified.pointsAfter},
                                         {"maxDeviationMm", simplified.maxDeviationMm}}
                : nlohmann::ordered_json(nullptr);
        const double simplifySeconds = watch.lap();
        SliceFields fields;
        {
            Progress progress("fields of " + roi->name, !global.quiet);
            RoiFieldOptions options;
            options.pixelMm = args.pixelMm;
            options.progress = [&](double f) { progress.update(f); };
            fields = sliceFieldsOf(runtime, slices, options);
        }
        const double fieldSeconds = watch.lap();
        const nlohmann::ordered_json files =
            writeRoiFields(*roi, stems[r], slices, fields, args, global);
        const double writeSeconds = watch.lap();
        reports.push_back(
            {{"roi", roi->name},
             {"slices", fields.sliceCount()},
             {"grid",
              {{"width", fields.grid.width},
               {"height", fields.grid.height},
               {"pixelMm", fields.grid.pixelMm}}},
             {"device", runtime.device().deviceName},
             {"simplification", simplification},
             {"seconds",
              {{"simplify", simplifySeconds}, {"fields", fieldSeconds}, {"write", writeSeconds}}},
             {"files", files}});
        if (!args.json)
            std::cout << roi->name << ": " << fields.sliceCount() << " slices on a "
                      << fields.grid.width << " x " << fields.grid.height << " grid of "
                      << fields.grid.pixelMm << " mm pixels, " << fieldSeconds << " s on "
                      << runtime.device().deviceName << "; wrote " << files.size() << " files to "
                      << args.outputDir << "\n";
    }
    if (args.json)
        std::cout << jsonText(nlohmann::ordered_json{{"command", "fields"},
                                                     {"input", args.input},
                                                     {"loadSeconds", loadSeconds},
                                                     {"rois", reports}},
                              2)
                  << "\n";
}

}  // namespace

void addFieldsCommand(CLI::App& root, const GlobalOptions& global) {
    auto args = std::make_shared<FieldsArgs>();
    CLI::App* cmd = root.add_subcommand(
        "fields", "Exact 2D signed distance fields and nearest-contour ids of every slice");
    cmd->footer(
        "Writes, per ROI, NAME-distance.nhdr/.raw (float32 mm, negative inside) and "
        "NAME-ids.nhdr/.raw (uint32 nearest primitive), which 3D Slicer and ParaView open, and "
        "NAME-fields.json describing the layout (docs/fields.md).");
    cmd->add_option("file", args->input, contourInputHelp())->required();
    cmd->add_option("-o,--output", args->outputDir, "Output folder (created if missing)")
        ->required()
        ->check(kNotStandardStream);
    cmd->add_option("--roi", args->roi, "ROI name (default: the only ROI of the file)");
    cmd->add_flag("--all", args->all, "Every ROI of the file");
    cmd->add_option("--pixel-mm", args->pixelMm,
                    "Pixel size in mm (default 0: the ROI's extent plus margin fits ~512 px)")
        ->capture_default_str()
        ->check(kNonNegative);
    cmd->add_flag("--png", args->png,
                  "Also write pictures: NAME-distance-NNN.png (blue inside, red outside, "
                  "iso-lines), NAME-ids-NNN.png (nearest primitive as hue) and NAME-medial-NNN.png "
                  "(sum with the next slice, medial axes in yellow)");
    cmd->add_option("--iso-mm", args->isoStepMm, "Iso-line spacing in the pictures, mm")
        ->capture_default_str()
        ->check(kPositive);
    cmd->add_option("--contour-error", args->contourErrorMm,
                    "Simplify contours first so every original point stays within this many mm "
                    "(0 = off); fields are then of the simplified contours")
        ->capture_default_str()
        ->check(kNonNegative);
    cmd->add_flag("--json", args->json, "Print a JSON report instead of text");
    asOutput(cmd->get_option("--output"), OutputKind::Folder);
    cmd->callback([args, &global] { runFields(*args, global); });
}

}  // namespace dfrecon::app
