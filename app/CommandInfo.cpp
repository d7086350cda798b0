// dfrecon info FILE: what a contour file (.slices or RTSTRUCT) holds (ROIs, slices, nesting,
// spacing, extent), after the same validation every command applies.
#include <iomanip>
#include <iostream>

#include <nlohmann/json.hpp>

#include "app/Commands.hpp"
#include "app/Inputs.hpp"
#include "io/contours/SlicesFile.hpp"
#include "io/files/JsonText.hpp"
#include "report/EnumNames.hpp"
#include "report/ExitCodes.hpp"
#include "report/Reports.hpp"

namespace dfrecon::app {

namespace {

nlohmann::ordered_json sliceJson(const Slice& slice) {
    const std::vector<int> depths = nestingDepths(slice);
    nlohmann::ordered_json contours = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < slice.contours.size(); ++i)
        contours.push_back({{"points", slice.contours[i].size()},
                            {"depth", depths[i]},
                            {"role", depths[i] % 2 == 0 ? "outer" : "hole"},
                            {"areaMm2", std::abs(signedArea(slice.contours[i]))}});
    return {{"zMm", slice.zMm}, {"contours", contours}};
}

nlohmann::ordered_json roiJson(const Roi& roi, const RtStructRoiInfo* dicom) {
    const Extent3 extent = patientExtentOf(roi);
    const SpacingStats spacing = spacingOf(roi);
    nlohmann::ordered_json slices = nlohmann::ordered_json::array();
    std::size_t holes = 0;
    for (const Slice& slice : roi.slices) {
        slices.push_back(sliceJson(slice));
        for (const auto& contour : slices.back()["contours"])
            holes += contour["depth"].get<int>() % 2;
    }
    nlohmann::ordered_json j = {{"name", roi.name},
                                {"number", valueOrNull(roi.number)},
                                {"slices", roi.slices.size()},
                                {"contours", roi.contourCount()},
                                {"holes", holes},
                                {"points", roi.pointCount()},
                                // The volume the text line shows: what the
                                // planning system's Σ area × spacing gives.
                                {"contourVolumeMm3", contourVolumeMm3(roi)},
                                {"contourVolumeCc", contourVolumeMm3(roi) / 1000},
                                {"spacingMm",
                                 {{"min", spacing.minMm},
                                  {"max", spacing.maxMm},
                                  {"mean", spacing.meanMm},
                                  {"uniform", spacing.uniform}}},
                                {"planes", roi.frame.orientationName()},
                                {"planeNormal", xyzJson(roi.frame.n)},
                                {"perSlice", slices},
                                {"contourReading", contourReadingJson(roi.reading)}};
    if (dicom) {
        j["holeConvention"] = nameOf(kHoleConventionNames, dicom->holes);
        j["contoursSkipped"] = dicom->contoursSkipped;
        j["slabThicknessMm"] = valueOrNull(roi.slabThicknessMm > 0, roi.slabThicknessMm);
    }
    j["colour"] =
        roi.colour ? nlohmann::ordered_json(*roi.colour) : nlohmann::ordered_json(nullptr);
    if (dicom)
        j["interpretedType"] = valueOrNull(!roi.interpretedType.empty(), roi.interpretedType);
    if (!extent.empty) j["extentMm"] = {{"min", xyzJson(extent.min)}, {"max", xyzJson(extent.max)}};
    return j;
}

// Slice positions are along the plane normal: for a patient axis (the
// canonical frames readers give) that is the patient coordinate itself.
std::string planeAxisName(const PlaneFrame& frame) {
    if (frame.n == Vec3{0, 0, 1}) return "z";
    if (frame.n == Vec3{1, 0, 0}) return "x";
    if (frame.n == Vec3{0, 1, 0}) return "y";
    return "n";
}

std::string counted(std::size_t n, const std::string& noun) {
    return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

// One line per ROI: what a user checks first (planes, contours, the volume
// the planning system shows, where it lies).
void printRoiSummary(const Roi& roi) {
    std::cout << "  ";
    if (roi.number) std::cout << std::setw(3) << *roi.number << " ";
    std::cout << "\"" << roi.name << "\": " << counted(roi.slices.size(), "plane") << ", "
              << counted(roi.contourCount(), "contour") << ", " << std::setprecision(6)
              << contourVolumeMm3(roi) / 1000 << " cc";
    const Extent3 extent = patientExtentOf(roi);
    if (!extent.empty) std::cout << ", z " << extent.min[2] << " .. " << extent.max[2] << " mm";
    if (roi.slices.size() > 1) {
        const SpacingStats spacing = spacingOf(roi);
        std::cout << ", spacing " << spacing.minMm
                  << (spacing.uniform ? "" : " .. " + std::to_string(spacing.maxMm)) << " mm";
    }
    if (!roi.frame.isIdentity()) std::cout << ", " << roi.frame.orientationName() << " planes";
    std::cout << "\n";
}

void printRoi(const Roi& roi, const RtStructRoiInfo* dicom) {
    const Extent3 extent = patientExtentOf(roi);
    const SpacingStats spacing = spacingOf(roi);
    std::cout << "ROI ";
    if (roi.number) std::cout << *roi.number << " ";
    std::cout << "\"" << roi.name << "\"";
    if (roi.colour)
        std::cout << " (colour " << int((*roi.colour)[0]) << " " << int((*roi.colour)[1]) << " "
                  << int((*roi.colour)[2]) << ")";
    std::cout << ": " << counted(roi.slices.size(), "slice") << ", "
              << counted(roi.contourCount(), "contour") << ", "
              << counted(roi.pointCount(), "point");
    if (dicom) {
        if (dicom->holes != HoleConvention::None)
            std::cout << ", holes drawn " << nameOf(kHoleConventionNames, dicom->holes);
        if (dicom->contoursSkipped > 0)
            std::cout << ", " << counted(dicom->contoursSkipped, "contour") << " skipped";
        if (!dicom->hasContourSequence) std::cout << " (no ContourSequence: empty)";
    }
    if (!roi.frame.isIdentity()) std::cout << ", " << roi.frame.orientationName() << " planes";
    std::cout << "\n";
    if (extent.empty) return;
    std::cout << "  extent x " << extent.min[0] << " .. " << extent.max[0] << ", y "
              << extent.min[1] << " .. " << extent.max[1] << ", z " << extent.min[2] << " .. "
              << extent.max[2] << " mm (patient LPS)\n";
    if (roi.slices.size() > 1)
        std::cout << "  spacing " << (spacing.uniform ? "uniform " : "uneven ") << spacing.minMm
                  << (spacing.uniform ? "" : " .. " + std::to_string(spacing.maxMm)) << " mm\n";
    const std::string axis = planeAxisName(roi.frame);
    if (axis == "n")
        std::cout << "  planes at n = position along the normal (" << roi.frame.n.x << ", "
                  << roi.frame.n.y << ", " << roi.frame.n.z << ")\n";
    for (const Slice& slice : roi.slices) {
        int holes = 0;
        for (int depth : nestingDepths(slice)) holes += depth % 2;
        std::cout << "  " << axis << " " << std::setw(9) << slice.zMm << ": "
                  << counted(slice.contours.size(), "contour");
        if (holes > 0) std::cout << " (" << counted(std::size_t(holes), "hole") << ")";
        std::cout << "\n";
    }
}

// ROIs the reader could not read: said on stderr, and the command exits 2
// once the rest is reported.
void reportDefects(const ContourSet& contours) {
    std::size_t defects = 0;
    for (const Roi& roi : contours.rois)
        if (roi.defect) {
            std::cerr << "dfrecon: " << roi.defect->what() << "\n";
            ++defects;
        }
    if (defects > 0)
        throw ItemsFailed(std::to_string(defects) + " ROI(s) could not be read; the others could",
                          kExitBadInput);
}

void runInfo(const GlobalOptions& global, const std::string& path, bool json, bool perPlane) {
    const ContourInput load = loadContours(path, global);
    if (json) {
        nlohmann::ordered_json rois = nlohmann::ordered_json::array();
        for (const Roi& roi : load.contours.rois) {
            rois.push_back(roiJson(roi, load.dicomInfo(roi)));
            if (roi.defect) rois.back()["error"] = roi.defect->what();
        }
        nlohmann::ordered_json warnings = nlohmann::ordered_json::array();
        for (const InputWarning& w : load.warnings) warnings.push_back(w.toString());
        nlohmann::ordered_json report{
            {"command", "info"}, {"file", path}, {"format", contourFormatName(load.format)}};
        if (load.format == ContourFormat::LabelVolume || load.format == ContourFormat::MaskStack)
            report["labelTable"] = load.labelTable.empty()
                                       ? nlohmann::ordered_json(nullptr)
                                       : nlohmann::ordered_json(load.labelTable);
        report["rois"] = rois;
        report["warnings"] = warnings;
        std::cout << jsonText(report, 2) << "\n";
        reportDefects(load.contours);
        return;
    }
    std::cout << path << " (" << contourFormatName(load.format)
              << "): " << counted(load.contours.rois.size(), "ROI");
    if (!load.labelTable.empty()) std::cout << ", names from " << load.labelTable;
    std::cout << "\n";
    std::size_t contours = 0, planes = 0;
    for (const Roi& roi : load.contours.rois) {
        contours += roi.contourCount();
        planes += roi.slices.size();
    }
    if (!perPlane)
        std::cout << counted(planes, "plane") << " and " << counted(contours, "contour")
                  << " in all (--slices lists every plane)\n";
    for (const Roi& roi : load.contours.rois) {
        if (perPlane)
            printRoi(roi, load.dicomInfo(roi));
        else
            printRoiSummary(roi);
        if (roi.defect) std::cout << "  NOT READ: " << roi.defect->problem() << "\n";
    }
    reportDefects(load.contours);
}

}  // namespace

void addInfoCommand(CLI::App& root, const GlobalOptions& global) {
    struct Args {
        std::string path;
        bool json = false, slices = false;
    };
    auto args = std::make_shared<Args>();
    CLI::App* cmd = root.add_subcommand(
        "info", "Validate a contour file and summarise it: ROIs, slices, contours, holes, extent");
    cmd->add_option("file", args->path, contourInputHelp())->required();
    cmd->add_flag("--slices", args->slices,
                  "Every ROI in full (colour, holes, extent, spacing) and every plane with its "
                  "contours and holes; by default one line per ROI");
    cmd->add_flag("--json", args->json, "Print a JSON report instead of text (always in full)");
    cmd->callback([&global, args] { runInfo(global, args->path, args->json, args->slices); });
}

}  // namespace dfrecon::app
