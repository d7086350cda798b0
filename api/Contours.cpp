#include "dfrecon/Contours.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>
#include <sstream>

#include "contours/PlaneGaps.hpp"
#include "io/contours/RoiName.hpp"
#include "io/contours/SlicesFile.hpp"
#include "io/files/InputsInUse.hpp"
#include "io/labels/LabelInput.hpp"

namespace dfrecon {

namespace {

// Two points this close in z lie on one plane: well below any scanner's
// slice position precision, well above double rounding of typed values.
constexpr double kOnePlaneWithinMm = 1e-6;

std::string contourName(const RoiPoints& roi, std::size_t index) {
    return "ROI '" + roi.name + "', contour " + std::to_string(index);
}

// What the .slices reader cannot say about points that never were text: a
// coordinate that is not a number, or a contour off its plane.
void checkPoints(const RoiPoints& roi, const std::string& source) {
    if (roi.contours.empty()) throw InputError(source, 0, "ROI '" + roi.name + "' has no contours");
    for (std::size_t c = 0; c < roi.contours.size(); ++c) {
        const std::vector<Vec3>& points = roi.contours[c];
        if (points.size() < 3)
            throw InputError(source, 0,
                             contourName(roi, c) + ": a contour needs at least 3 points, got " +
                                 std::to_string(points.size()));
        for (std::size_t k = 0; k < points.size(); ++k) {
            const Vec3& p = points[k];
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                throw InputError(source, 0,
                                 contourName(roi, c) + ", point " + std::to_string(k) +
                                     ": coordinate is not a finite number");
            if (std::abs(p.z - points[0].z) > kOnePlaneWithinMm)
                throw InputError(source, 0,
                                 contourName(roi, c) + ": not on one axial plane (z " +
                                     std::to_string(points[0].z) + " at point 0, " +
                                     std::to_string(p.z) + " at point " + std::to_string(k) +
                                     " mm); contours lie on planes of constant z");
        }
    }
}

// Contours grouped by plane (their first point's z), in increasing z;
// `arrayOf[s][c]` is the index in points.contours of slice s's contour c.
Roi asSlices(const RoiPoints& points, std::vector<std::vector<std::size_t>>& arrayOf) {
    std::map<double, std::pair<Slice, std::vector<std::size_t>>> planes;
    for (std::size_t a = 0; a < points.contours.size(); ++a) {
        const std::vector<Vec3>& contour = points.contours[a];
        auto& [slice, arrays] = planes[contour[0].z];
        slice.zMm = contour[0].z;
        Polygon polygon;
        polygon.reserve(contour.size());
        for (const Vec3& p : contour) polygon.push_back({p.x, p.y});
        slice.contours.push_back(std::move(polygon));
        arrays.push_back(a);
    }
    Roi roi;
    roi.name = points.name;
    roi.colour = points.colour;
    arrayOf.clear();
    for (auto& [z, plane] : planes) {
        roi.slices.push_back(std::move(plane.first));
        arrayOf.push_back(std::move(plane.second));
    }
    return roi;
}

// What each line of formatSlices' text stands for among the arrays given
// (its layout: two header lines; per ROI a line, per plane a line, per
// contour a line and then one per point), so that the reader's messages can
// name the ROI, the contour's index and the point instead of a line of text
// the user never saw. Index 0 is unused (lines count from 1).
std::vector<std::string> lineOrigins(
    const ContourSet& set, const std::vector<std::vector<std::vector<std::size_t>>>& arrayOf) {
    std::vector<std::string> origins(3, "");
    for (std::size_t r = 0; r < set.rois.size(); ++r) {
        const Roi& roi = set.rois[r];
        const std::string name = "ROI '" + roi.name + "'";
        origins.push_back(name);
        for (std::size_t s = 0; s < roi.slices.size(); ++s) {
            std::ostringstream plane;
            plane << name << ", plane z = " << roi.slices[s].zMm << " mm";
            origins.push_back(plane.str());
            for (std::size_t c = 0; c < roi.slices[s].contours.size(); ++c) {
                const std::string contour = name + ", contour " + std::to_string(arrayOf[r][s][c]);
                origins.push_back(contour);
                for (std::size_t k = 0; k < roi.slices[s].contours[c].size(); ++k)
                    origins.push_back(contour + ", point " + std::to_string(k));
            }
        }
    }
    return origins;
}

// The point a line stands for ("point 7" of "ROI 'A', contour 2, point 7"),
// or the line itself where it is no point.
std::string pointOf(const std::string& lineNumber, const std::vector<std::string>& origins) {
    const std::size_t n = std::stoul(lineNumber);
    const std::string& origin = n < origins.size() ? origins[n] : std::string();
    const std::size_t at = origin.rfind(", point ");
    return at == std::string::npos ? "line " + lineNumber : origin.substr(at + 8);
}

// `text` with every "line N" replaced by what line N stands for, and a
// segment's "(lines A-B)" by its points.
std::string relocated(std::string text, const std::vector<std::string>& origins) {
    static const std::regex segment("\\(lines ([0-9]+)-([0-9]+)\\)");
    std::smatch m;
    while (std::regex_search(text, m, segment))
        text = m.prefix().str() + "(points " + pointOf(m[1].str(), origins) + "-" +
               pointOf(m[2].str(), origins) + ")" + m.suffix().str();
    static const std::regex line("line ([0-9]+)");
    std::string out;
    std::size_t from = 0;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), line);
         it != std::sregex_iterator(); ++it) {
        const std::size_t n = std::stoul((*it)[1].str());
        out += text.substr(from, std::size_t(it->position()) - from);
        out += n < origins.size() && !origins[n].empty() ? origins[n] : it->str();
        from = std::size_t(it->position() + it->length());
    }
    return out + text.substr(from);
}

std::string originOf(int line, const std::vector<std::string>& origins) {
    return line > 0 && std::size_t(line) < origins.size() ? origins[std::size_t(line)] : "";
}

// A warning for an ROI whose planes are unevenly spaced within a run (the
// gaps where it ends and starts again do not count), by spacingOf's rule.
void warnUnevenSpacing(ContoursRead& read, const Roi& roi, const std::string& source) {
    double smallest = INFINITY, largest = 0;
    for (std::size_t i = 1; i < roi.slices.size(); ++i) {
        if (std::find(roi.restartsAt.begin(), roi.restartsAt.end(), i) != roi.restartsAt.end())
            continue;
        const double gap = roi.slices[i].zMm - roi.slices[i - 1].zMm;
        smallest = std::min(smallest, gap);
        largest = std::max(largest, gap);
    }
    if (largest - smallest <= kUniformSpacingToleranceMm) return;
    std::ostringstream range;
    range << smallest << " to " << largest;
    read.warnings.push_back({source, 0,
                             "ROI '" + roi.name + "': uneven slice spacing, " + range.str() + " mm",
                             roi.name});
}

// Where ROIs end and start again across planes left empty
// (contours/PlaneGaps), with a warning for each such ROI, and for each ROI
// unevenly spaced within its runs.
void findGaps(ContoursRead& read, const std::string& source) {
    findPlaneGaps(read.contours);
    for (const Roi& roi : read.contours.rois) {
        warnUnevenSpacing(read, roi, source);
        // One plane and no other plane or slab thickness in the file: no
        // thickness is known, which the reports would otherwise hide.
        if (roi.slices.size() == 1 && lonePlaneThicknessMm(roi) <= 0)
            read.warnings.push_back({source, 0,
                                     "ROI '" + roi.name +
                                         "' lies on one plane and nothing gives its thickness (no "
                                         "other plane, no slab thickness): its contour volume "
                                         "counts 0 and its surface stands 1 mm thick (the cap "
                                         "offset sets how far it reaches each side)",
                                     roi.name});
        if (roi.restartsAt.empty()) continue;
        std::ostringstream where;
        for (std::size_t k = 0; k < roi.restartsAt.size(); ++k) {
            const std::size_t i = roi.restartsAt[k];
            where << (k ? ", " : "") << roi.slices[i - 1].zMm << " to " << roi.slices[i].zMm;
        }
        read.warnings.push_back({source, 0,
                                 "ROI '" + roi.name + "' has planes left empty between " +
                                     where.str() + " mm: it ends and starts again there (" +
                                     std::to_string(roi.restartsAt.size() + 1) +
                                     " pieces), as planning systems count its volume",
                                 roi.name});
    }
}

ContoursRead fromSlicesLoad(SlicesLoad load, const std::string& source) {
    ContoursRead read;
    read.format = ContourFormat::Slices;
    read.contours = std::move(load.contours);
    read.warnings = std::move(load.warnings);
    findGaps(read, source);
    return read;
}

}  // namespace

const RtStructRoiInfo* ContoursRead::dicomInfo(const Roi& roi) const {
    const std::size_t i = std::size_t(&roi - contours.rois.data());
    return i < dicomRois.size() ? &dicomRois[i] : nullptr;
}

ContoursRead readContours(const std::string& path, const ReadContoursOptions& options) {
    // Decided once: the format and a label volume's table.
    const ContourSource source = contourSourceOf(path, options.labelTable);
    ContoursRead read;
    read.format = source.format;
    switch (read.format) {
        case ContourFormat::LabelVolume:
        case ContourFormat::MaskStack: {
            LabelContours labels = readLabelContours(source, options.acceptIntensity);
            read.contours = std::move(labels.contours);
            read.labelTable = std::move(labels.namesFrom);
            break;
        }
        case ContourFormat::RtStruct: {
            RtStructLoad load = readRtStruct(path);
            read.contours = std::move(load.contours);
            read.warnings = std::move(load.warnings);
            read.dicomRois = std::move(load.rois);
            break;
        }
        case ContourFormat::Slices:
            read = fromSlicesLoad(readSlicesFile(path, {}, options.progress), path);
            break;
    }
    if (read.format != ContourFormat::Slices) findGaps(read, path);
    // Every reader makes names by the rule (io/contours/RoiName); this is the one
    // place that holds for all of them, so that no name read here can fail
    // at a write or fail to read back.
    for (Roi& roi : read.contours.rois) {
        const std::string problem = roiNameProblem(roi.name);
        if (problem.empty()) continue;
        std::string mended = mendedRoiName(roi.name);
        // The warnings made about it so far follow it to its new name.
        for (InputWarning& w : read.warnings)
            if (w.roi == roi.name) w.roi = mended;
        read.warnings.push_back(
            {path, 0, "an ROI name " + problem + "; read as '" + mended + "'", mended});
        roi.name = std::move(mended);
    }
    return read;
}

ContoursRead readSlicesStream(std::istream& in, const std::string& name,
                              const ReadContoursOptions& /*options: none applies*/) {
    // The parser's limits bound what a pipe can make it hold, as they bound a file.
    const ReadingInput reading(name);
    return fromSlicesLoad(parseSlices(in, name), name);
}

ContoursRead structureSetFromPoints(const std::vector<RoiPoints>& rois, const std::string& source,
                                    const ReadContoursOptions& options) {
    ContourSet set;
    std::vector<std::vector<std::vector<std::size_t>>> arrayOf(rois.size());
    for (std::size_t r = 0; r < rois.size(); ++r) {
        checkPoints(rois[r], source);
        set.rois.push_back(asSlices(rois[r], arrayOf[r]));
    }
    // Through the .slices reader, so that points in memory are repaired,
    // validated and oriented by the very rules a file is (formatSlices
    // writes every double exactly): one set of rules, one set of messages,
    // which then name the arrays instead of lines of that text.
    std::stringstream text;
    formatSlices(set, text);
    const std::vector<std::string> origins = lineOrigins(set, arrayOf);
    auto located = [&](int line, const std::string& problem) {
        const std::string origin = originOf(line, origins);
        return (origin.empty() ? "" : origin + ": ") + relocated(problem, origins);
    };
    ContoursRead read;
    try {
        read = readSlicesStream(text, source, options);
    } catch (const InputError& e) {
        throw InputError(source, 0, located(e.line(), e.problem()));
    }
    for (InputWarning& w : read.warnings) {
        w.message = located(w.line, w.message);
        w.line = 0;
    }
    for (Roi& roi : read.contours.rois)
        if (roi.defect)
            roi.defect = InputError(source, 0, located(roi.defect->line(), roi.defect->problem()));
    return read;
}

}  // namespace dfrecon
