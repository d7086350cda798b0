#include "app/Inputs.hpp"

#include <cctype>
#include <iostream>
#include <stdexcept>

#include "app/Progress.hpp"

namespace dfrecon::app {

SlicesLoad loadContours(const std::string& path, const GlobalOptions& global) {
    SlicesLoad load;
    {
        Progress progress("reading " + path, !global.quiet);
        load = readSlicesFile(path, {}, [&](double f) { progress.update(f); });
    }
    if (!global.quiet)
        for (const InputWarning& w : load.warnings) std::cerr << w.toString() << "\n";
    return load;
}

static std::string roiNames(const ContourSet& contours) {
    std::string names;
    for (const Roi& roi : contours.rois) names += (names.empty() ? "" : ", ") + roi.name;
    return names.empty() ? "(none)" : names;
}

std::vector<const Roi*> selectRois(const ContourSet& contours, const std::string& name, bool all) {
    std::vector<const Roi*> chosen;
    if (all) {
        for (const Roi& roi : contours.rois)
            if (!roi.slices.empty()) chosen.push_back(&roi);
        if (chosen.empty()) throw std::invalid_argument("no ROI has contours");
        return chosen;
    }
    if (!name.empty()) {
        if (const Roi* roi = contours.findRoi(name)) return {roi};
        throw std::invalid_argument("no ROI named '" + name +
                                    "'; available: " + roiNames(contours));
    }
    if (contours.rois.size() == 1) return {&contours.rois.front()};
    throw std::invalid_argument(
        "the file holds several ROIs; choose one with --roi NAME or use "
        "--all (available: " +
        roiNames(contours) + ")");
}

std::string fileStem(const std::string& name) {
    std::string stem;
    for (char c : name)
        stem += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.'
                    ? c
                    : '_';
    return stem.empty() ? "roi" : stem;
}

}  // namespace dfrecon::app
