#include "dfrecon/Contours.hpp"

#include <cmath>
#include <map>
#include <sstream>

#include "io/InputsInUse.hpp"
#include "io/LabelInput.hpp"
#include "io/SlicesFile.hpp"

namespace dfrecon {

namespace {

// Two points this close in z lie on one plane: well below any scanner's
// slice position precision, well above double rounding of typed values.
constexpr double kSamePlaneMm = 1e-6;

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
            if (std::abs(p.z - points[0].z) > kSamePlaneMm)
                throw InputError(source, 0,
                                 contourName(roi, c) + ": not on one axial plane (z " +
                                     std::to_string(points[0].z) + " at point 0, " +
                                     std::to_string(p.z) + " at point " + std::to_string(k) +
                                     " mm); contours lie on planes of constant z");
        }
    }
}

// Contours grouped by plane (their first point's z), in increasing z.
Roi asSlices(const RoiPoints& points) {
    std::map<double, Slice> planes;
    for (const std::vector<Vec3>& contour : points.contours) {
        Slice& slice = planes[contour[0].z];
        slice.zMm = contour[0].z;
        Polygon polygon;
        polygon.reserve(contour.size());
        for (const Vec3& p : contour) polygon.push_back({p.x, p.y});
        slice.contours.push_back(std::move(polygon));
    }
    Roi roi;
    roi.name = points.name;
    roi.colour = points.colour;
    for (auto& [z, slice] : planes) roi.slices.push_back(std::move(slice));
    return roi;
}

ContoursRead fromSlicesLoad(SlicesLoad load) {
    ContoursRead read;
    read.format = ContourFormat::Slices;
    read.contours = std::move(load.contours);
    read.warnings = std::move(load.warnings);
    return read;
}

}  // namespace

const RtStructRoiInfo* ContoursRead::dicomInfo(const Roi& roi) const {
    const std::size_t i = std::size_t(&roi - contours.rois.data());
    return i < dicomRois.size() ? &dicomRois[i] : nullptr;
}

ContoursRead readContours(const std::string& path, const ReadContoursOptions& options) {
    const ContourRepairOptions repair{options.repairSelfCrossings};
    ContoursRead read;
    read.format = contourFormatOf(path);
    switch (read.format) {
        case ContourFormat::LabelVolume:
        case ContourFormat::MaskStack: {
            const LabelInputOptions label{options.labelTable, options.acceptIntensity};
            read.contours = readLabelContours(path, label);
            read.labelTable = labelTableSource(path, label);
            break;
        }
        case ContourFormat::RtStruct: {
            RtStructLoad load = readRtStruct(path, {}, repair);
            read.contours = std::move(load.contours);
            read.warnings = std::move(load.warnings);
            read.dicomRois = std::move(load.rois);
            break;
        }
        case ContourFormat::Slices:
            read = fromSlicesLoad(readSlicesFile(path, {}, options.progress, repair));
            break;
    }
    return read;
}

ContoursRead readSlicesStream(std::istream& in, const std::string& name,
                              const ReadContoursOptions& options) {
    // The parser's limits bound what a pipe can make it hold, as they bound a file.
    const ReadingInput reading(name);
    return fromSlicesLoad(
        parseSlices(in, name, {}, {}, ContourRepairOptions{options.repairSelfCrossings}));
}

ContoursRead structureSetFromPoints(const std::vector<RoiPoints>& rois, const std::string& source,
                                    const ReadContoursOptions& options) {
    ContourSet set;
    for (const RoiPoints& roi : rois) {
        checkPoints(roi, source);
        set.rois.push_back(asSlices(roi));
    }
    // Through the .slices reader, so that points in memory are repaired,
    // validated and oriented by the very rules a file is (formatSlices
    // writes every double exactly): one set of rules, one set of messages.
    std::stringstream text;
    formatSlices(set, text);
    return readSlicesStream(text, source, options);
}

}  // namespace dfrecon
