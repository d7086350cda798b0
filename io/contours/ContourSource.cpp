#include "io/contours/ContourSource.hpp"

#include "io/labels/LabelTable.hpp"

namespace dfrecon {

ContourSource contourSourceOf(const std::string& path, const std::string& givenLabelTable) {
    ContourSource source;
    source.path = path;
    source.format = contourFormatOf(path);
    if (!givenLabelTable.empty()) {
        source.labelTablePath = givenLabelTable;
        source.tableGiven = true;
    } else if (source.format == ContourFormat::LabelVolume) {
        source.labelTablePath = labelTableBeside(path).value_or("");
    }
    return source;
}

}  // namespace dfrecon
