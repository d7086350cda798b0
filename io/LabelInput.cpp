#include "io/LabelInput.hpp"

#include <algorithm>
#include <cctype>

#include "io/LabelVolume.hpp"
#include "io/MaskContours.hpp"
#include "io/MaskStack.hpp"

namespace dfrecon {

namespace {

bool endsWith(const std::string& text, const std::string& end) {
    if (text.size() < end.size()) return false;
    return std::equal(end.rbegin(), end.rend(), text.rbegin(), [](char a, char b) {
        return a == std::tolower(static_cast<unsigned char>(b));
    });
}

bool isLabelVolumeName(const std::string& path) {
    for (const char* end : {".nrrd", ".nhdr", ".nii", ".nii.gz"})
        if (endsWith(path, end)) return true;
    return false;
}

}  // namespace

bool isLabelInputPath(const std::string& path) {
    return isLabelVolumeName(path) || isMaskStackPath(path);
}

ContourSet readLabelContours(const std::string& path) {
    MaskContourOptions options;
    options.sourceName = path;
    if (isLabelVolumeName(path)) return contoursFromLabels(readLabelVolume(path), options);
    MaskStack stack = readMaskStack(path);
    options.names = std::move(stack.labelNames);
    options.planePositionsMm = std::move(stack.slicePositionsMm);
    return contoursFromLabels(stack.volume, options);
}

}  // namespace dfrecon
