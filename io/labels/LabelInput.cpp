#include "io/labels/LabelInput.hpp"

#include <algorithm>
#include <sstream>
#include <unordered_set>

#include "io/contours/ContourFormat.hpp"
#include "io/files/FileNames.hpp"
#include "io/labels/LabelTable.hpp"
#include "io/labels/MaskContours.hpp"
#include "io/labels/MaskStack.hpp"

namespace dfrecon {

namespace {

bool hasSegments(const LabelVolume& volume) {
    return std::any_of(volume.keyValues.begin(), volume.keyValues.end(),
                       [](const auto& kv) { return kv.first.rfind("Segment0_", 0) == 0; });
}

// The names and colours of `table` as contouring options.
void applyTable(const LabelTable& table, MaskContourOptions& options) {
    for (const auto& [label, entry] : table) {
        options.names[label] = entry.name;
        if (entry.colour) options.colours[label] = *entry.colour;
    }
}

}  // namespace

std::optional<std::string> intensityImageEvidence(const LabelVolume& volume) {
    const auto& g = volume.geometry;
    const auto& labels = volume.labels;
    std::unordered_set<std::int32_t> values;
    std::size_t pairs = 0, changes = 0;
    for (std::size_t at = 0; at < g.voxelCount(); ++at) {  // the first layer
        const std::int32_t v = labels[at];
        if (v == 0) continue;
        if (values.size() < kIntensityMinValues) values.insert(v);
        const std::size_t i = at % std::size_t(g.size[0]);
        const std::size_t j = at / std::size_t(g.size[0]) % std::size_t(g.size[1]);
        if (i + 1 < std::size_t(g.size[0]) && labels[at + 1] != 0) {
            ++pairs;
            changes += labels[at + 1] != v;
        }
        const std::size_t below = at + std::size_t(g.size[0]);
        if (j + 1 < std::size_t(g.size[1]) && labels[below] != 0) {
            ++pairs;
            changes += labels[below] != v;
        }
    }
    if (values.size() < kIntensityMinValues || pairs == 0) return std::nullopt;
    const double fraction = double(changes) / double(pairs);
    if (fraction <= kIntensityChangeFraction) return std::nullopt;
    std::ostringstream why;
    why << "looks like an intensity image, not a label map: " << kIntensityMinValues
        << " or more distinct values, and " << int(fraction * 100 + 0.5)
        << " % of neighbouring non-zero voxels differ (a label map changes only on region "
           "borders). Segment or threshold it first, or pass --accept-intensity to contour every "
           "value";
    return why.str();
}

LabelContours readLabelContours(const ContourSource& source, bool acceptIntensityImages) {
    const std::string& path = source.path;
    LabelContours out;
    MaskContourOptions contouring;
    contouring.sourceName = path;
    if (source.format == ContourFormat::MaskStack) {
        MaskStack stack = readMaskStack(path);
        contouring.names = std::move(stack.labelNames);
        contouring.planePositionsMm = std::move(stack.slicePositionsMm);
        if (source.tableGiven) {
            applyTable(readLabelTable(source.labelTablePath), contouring);
            out.namesFrom = source.labelTablePath;
        }
        out.contours = contoursFromLabels(stack.volume, contouring);
        return out;
    }
    const LabelVolume volume = readLabelVolume(path);
    if (!acceptIntensityImages)
        if (const auto evidence = intensityImageEvidence(volume))
            throw InputError(path, 0, *evidence);
    // Names: the table given, else a segmentation's own segments (each
    // layer's, below), else the table beside the volume.
    const bool segmentNames = !source.tableGiven && hasSegments(volume);
    if (segmentNames) {
        out.namesFrom = "segmentation header";
    } else if (!source.labelTablePath.empty()) {
        applyTable(readLabelTable(source.labelTablePath), contouring);
        out.namesFrom = source.labelTablePath;
    }
    auto contourLayer = [&](const LabelVolume& labels, int layer) {
        MaskContourOptions layerContouring = contouring;
        if (segmentNames)
            applyTable(labelTableFromSegmentation(path, volume.keyValues, layer, volume.layerCount),
                       layerContouring);
        return contoursFromLabels(labels, layerContouring);
    };
    if (volume.layerCount == 1) {
        out.contours = contourLayer(volume, 0);
        return out;
    }
    // A segmentation whose segments overlap: each layer a label map of its
    // own segments (a label value may recur on another layer), the ROIs of
    // all layers in one set.
    LabelVolume layer;
    layer.geometry = volume.geometry;
    for (int l = 0; l < volume.layerCount; ++l) {
        const std::int32_t* labels = layerLabels(volume, l);
        layer.labels.assign(labels, labels + volume.geometry.voxelCount());
        ContourSet part = contourLayer(layer, l);
        for (Roi& roi : part.rois) out.contours.rois.push_back(std::move(roi));
    }
    return out;
}

ContourSet readLabelContours(const std::string& path, const LabelInputOptions& options) {
    return readLabelContours(contourSourceOf(path, options.labelTablePath),
                             options.acceptIntensityImages)
        .contours;
}

}  // namespace dfrecon
