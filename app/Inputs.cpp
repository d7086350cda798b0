#include "app/Inputs.hpp"

#include <algorithm>
#include <cctype>
#include <iostream>
#include <map>
#include <set>
#include <stdexcept>

#include "app/Progress.hpp"
#include "app/StandardStreams.hpp"

namespace dfrecon::app {

static const Roi* findByNameOrNumber(const ContourSet& contours, const std::string& name) {
    if (const Roi* roi = contours.findRoi(name)) return roi;
    const bool digits = !name.empty() && name.size() < 10 &&
                        name.find_first_not_of("0123456789") == std::string::npos;
    return digits ? contours.findRoiNumber(std::stoi(name)) : nullptr;
}

// The warnings `onlyRois` asks for (all when it is empty or names an ROI
// the file lacks: the command's own error follows), and how many are left out.
static void printWarnings(const ContourInput& input, const std::vector<std::string>& onlyRois) {
    std::vector<std::string> names;
    for (const std::string& wanted : onlyRois) {
        const Roi* roi = findByNameOrNumber(input.contours, wanted);
        if (!roi) {
            names.clear();
            break;
        }
        names.push_back(roi->name);
    }
    std::size_t hidden = 0;
    for (const InputWarning& w : input.warnings) {
        const bool shown = names.empty() || w.roi.empty() ||
                           std::find(names.begin(), names.end(), w.roi) != names.end();
        if (shown)
            std::cerr << w.toString() << "\n";
        else
            ++hidden;
    }
    if (hidden > 0)
        std::cerr << "dfrecon: " << hidden << " warning" << (hidden == 1 ? "" : "s")
                  << " about other ROIs not shown (dfrecon info lists every one)\n";
}

ContourInput loadContours(const std::string& path, const GlobalOptions& global,
                          const std::vector<std::string>& onlyRois) {
    ReadContoursOptions options;
    options.labelTable = global.labelTable;
    options.acceptIntensity = global.acceptIntensity;
    ContourInput input;
    if (isStandardStream(path)) {
        // Only .slices streams (app/StandardStreams.hpp).
        input = readSlicesStream(std::cin, kStandardInputName, options);
    } else {
        Progress progress("reading " + path, !global.quiet);
        options.progress = [&](double f) { progress.update(f); };
        input = readContours(path, options);
    }
    if (!global.quiet) printWarnings(input, onlyRois);
    return input;
}

static std::string roiNames(const ContourSet& contours) {
    std::string names;
    for (const Roi& roi : contours.rois) {
        names += (names.empty() ? "" : ", ") + roi.name;
        if (roi.number) names += " (" + std::to_string(*roi.number) + ")";
        if (roi.slices.empty()) names += " [empty]";
    }
    return names.empty() ? "(none)" : names;
}

std::vector<const Roi*> selectRois(const ContourSet& contours, const std::string& name, bool all) {
    std::vector<const Roi*> chosen;
    if (all && !name.empty())
        throw std::invalid_argument("--roi " + name + " and --all exclude each other: give one");
    if (all) {
        // ROIs the reader could not read are chosen too, for the command to
        // report them among the others.
        for (const Roi& roi : contours.rois)
            if (!roi.slices.empty() || roi.defect) chosen.push_back(&roi);
        if (chosen.empty()) throw std::invalid_argument("no ROI has contours");
        return chosen;
    }
    const Roi* roi = nullptr;
    if (!name.empty()) {
        roi = findByNameOrNumber(contours, name);
        if (!roi)
            throw std::invalid_argument("no ROI named or numbered '" + name +
                                        "'; available: " + roiNames(contours));
    } else if (contours.rois.size() == 1) {
        roi = &contours.rois.front();
    } else {
        throw std::invalid_argument(
            "the file holds several ROIs; choose one with --roi NAME|NUMBER or use "
            "--all (available: " +
            roiNames(contours) + ")");
    }
    if (roi->defect) throw *roi->defect;
    if (roi->slices.empty())
        throw std::invalid_argument("ROI '" + roi->name + "' has no closed planar contours");
    return {roi};
}

std::string fileStem(const std::string& name) {
    std::string stem;
    for (char c : name.substr(0, kMaxStemBytes))
        stem += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ||
                        (c == '.' && !stem.empty())
                    ? c
                    : '_';
    return stem.empty() ? "roi" : stem;
}

std::vector<std::string> uniqueFileStems(const std::vector<const Roi*>& rois) {
    auto key = [](std::string stem) {
        for (char& c : stem) c = char(std::tolower(static_cast<unsigned char>(c)));
        return stem;
    };
    std::map<std::string, int> uses;
    for (const Roi* roi : rois) ++uses[key(fileStem(roi->name))];
    std::set<std::string> taken;
    std::vector<std::string> stems(rois.size());
    for (std::size_t i = 0; i < rois.size(); ++i) {
        const std::string stem = fileStem(rois[i]->name);
        if (uses[key(stem)] == 1) taken.insert(key(stems[i] = stem));
    }
    for (std::size_t i = 0; i < rois.size(); ++i) {
        if (!stems[i].empty()) continue;
        const std::string base =
            fileStem(rois[i]->name) + "_" + std::to_string(rois[i]->number.value_or(int(i) + 1));
        std::string stem = base;
        for (int k = 2; taken.count(key(stem)); ++k) stem = base + "_" + std::to_string(k);
        taken.insert(key(stems[i] = stem));
    }
    return stems;
}

}  // namespace dfrecon::app
