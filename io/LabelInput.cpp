#include "io/LabelInput.hpp"

#include <algorithm>
#include <sstream>
#include <unordered_set>

#include "io/ContourFormat.hpp"
#include "io/FileNames.hpp"
#include "io/LabelTable.hpp"
#include "io/MaskContours.hpp"
#include "io/MaskStack.hpp"

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

std::string labelTableSource(const std::string& path, const LabelInputOptions& options) {
    if (!options.labelTablePath.empty()) return options.labelTablePath;
    if (endsWithIgnoringCase(path, ".seg.nrrd")) return "segmentation header";
    return labelTableBeside(path).value_or("");
}

ContourSet readLabelContours(const std::string& path, const LabelInputOptions& options) {
    MaskContourOptions contouring;
    contouring.sourceName = path;
    if (contourFormatOf(path) == ContourFormat::MaskStack) {
        MaskStack stack = readMaskStack(path);
        contouring.names = std::move(stack.labelNames);
        contouring.planePositionsMm = std::move(stack.slicePositionsMm);
        if (!options.labelTablePath.empty())
            applyTable(readLabelTable(options.labelTablePath), contouring);
        return contoursFromLabels(stack.volume, contouring);
    }
    const LabelVolume volume = readLabelVolume(path);
    if (!options.acceptIntensityImages)
        if (const auto evidence = intensityImageEvidence(volume))
            throw InputError(path, 0, *evidence);
    // Names: the table given, else a segmentation's own segments (each
    // layer's, below), else the table beside the volume.
    const bool segmentNames = options.labelTablePath.empty() && hasSegments(volume);
    if (!options.labelTablePath.empty())
        applyTable(readLabelTable(options.labelTablePath), contouring);
    else if (const auto beside = labelTableBeside(path); beside && !segmentNames)
        applyTable(readLabelTable(*beside), contouring);
    auto contourLayer = [&](const LabelVolume& labels, int layer) {
        MaskContourOptions layerContouring = contouring;
        if (segmentNames)
            applyTable(labelTableFromSegmentation(path, volume.keyValues, layer, volume.layerCount),
                       layerContouring);
        return contoursFromLabels(labels, layerContouring);
    };
    if (volume.layerCount == 1) return contourLayer(volume, 0);
    // A segmentation whose segments overlap: each layer a label map of its
    // own segments (a label value may recur on another layer), the ROIs of
    // all layers in one set.
    ContourSet set;
    LabelVolume layer;
    layer.geometry = volume.geometry;
    for (int l = 0; l < volume.layerCount; ++l) {
        const std::int32_t* labels = layerLabels(volume, l);
        layer.labels.assign(labels, labels + volume.geometry.voxelCount());
        ContourSet part = contourLayer(layer, l);
        for (Roi& roi : part.rois) set.rois.push_back(std::move(roi));
    }
    return set;
}

}  // namespace dfrecon
