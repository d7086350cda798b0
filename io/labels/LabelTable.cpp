#include "io/labels/LabelTable.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "contours/InputError.hpp"
#include "io/files/AtomicWrite.hpp"
#include "io/files/FileNames.hpp"
#include "io/files/RegularFile.hpp"
#include "io/files/TextEncoding.hpp"
#include "io/images/Colours.hpp"

namespace dfrecon {

namespace {

namespace fs = std::filesystem;

std::optional<long long> integerOf(const std::string& token) {
    long long value = 0;
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, value);
    if (ec != std::errc() || ptr != end) return std::nullopt;
    return value;
}

// Splits on blanks; a token in double quotes (ITK-SNAP's names) keeps its
// blanks. `quoted` says which tokens were.
std::vector<std::string> tokensOf(const std::string& line, std::vector<bool>& quoted) {
    std::vector<std::string> tokens;
    quoted.clear();
    std::size_t i = 0;
    while (i < line.size()) {
        if (std::isspace(static_cast<unsigned char>(line[i]))) {
            ++i;
            continue;
        }
        if (line[i] == '"') {
            const std::size_t close = line.find('"', i + 1);
            if (close == std::string::npos) throw std::invalid_argument("unclosed quote");
            tokens.push_back(line.substr(i + 1, close - i - 1));
            quoted.push_back(true);
            i = close + 1;
            continue;
        }
        std::size_t j = i;
        while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
        tokens.push_back(line.substr(i, j - i));
        quoted.push_back(false);
        i = j;
    }
    return tokens;
}

std::int32_t labelValue(long long value) {
    if (value < INT32_MIN || value > INT32_MAX)
        throw std::invalid_argument("label value " + std::to_string(value) + " outside int32");
    return std::int32_t(value);
}

std::uint8_t component(const std::string& token, const char* which) {
    const auto value = integerOf(token);
    if (!value || *value < 0 || *value > 255)
        throw std::invalid_argument(std::string(which) + " '" + token + "' is not in 0..255");
    return std::uint8_t(*value);
}

// A name as every writer can write it and every reader read it back (a
// label table, a .seg.nrrd header line, a file name, .slices).
std::string checkedName(const std::string& name) {
    if (name.empty()) throw std::invalid_argument("empty name");
    if (name.size() > kMaxLabelNameBytes)
        throw std::invalid_argument("name longer than " + std::to_string(kMaxLabelNameBytes) +
                                    " bytes");
    for (const char c : name)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) {
            char code[8];
            std::snprintf(code, sizeof code, "0x%02X", unsigned(static_cast<unsigned char>(c)));
            throw std::invalid_argument("a control character (" + std::string(code) +
                                        ") in the name");
        }
    return name;
}

// Whether a token is meant as a number, good or bad ("1e9", "nan", "-3"):
// such tokens after a name are its colour and must be one.
bool meantAsNumber(const std::string& token) {
    if (token.empty()) return false;
    const char c = token[0];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.')
        return true;
    std::string lower;
    for (const char ch : token) lower += char(std::tolower(static_cast<unsigned char>(ch)));
    return lower == "nan" || lower == "inf" || lower == "infinity";
}

// One line in whichever form it has: (value, entry).
std::pair<std::int32_t, LabelEntry> entryOfLine(const std::vector<std::string>& t,
                                                const std::vector<bool>& quoted) {
    const auto first = integerOf(t[0]);
    // ITK-SNAP: IDX R G B A VIS MSH "LABEL" (A a float in 0..1).
    if (t.size() == 8 && first && quoted[7]) {
        return {labelValue(*first),
                {checkedName(t[7]),
                 Rgb{component(t[1], "red"), component(t[2], "green"), component(t[3], "blue")}}};
    }
    // FreeSurfer LUT / Slicer colour table: VALUE NAME R G B [A]; a colour
    // that is out of range or no integer ("1e9", "nan") is an error, not a
    // plain-list line's trailing words.
    if ((t.size() == 5 || t.size() == 6) && first && !integerOf(t[1]) && meantAsNumber(t[2]) &&
        meantAsNumber(t[3]) && meantAsNumber(t[4])) {
        return {labelValue(*first),
                {checkedName(t[1]),
                 Rgb{component(t[2], "red"), component(t[3], "green"), component(t[4], "blue")}}};
    }
    // AAL (v4): ABBREVIATION NAME VALUE.
    if (t.size() == 3 && !first && !integerOf(t[1]) && integerOf(t[2]))
        return {labelValue(*integerOf(t[2])), {checkedName(t[1]), std::nullopt}};
    // Plain list: VALUE NAME [anything].
    if (t.size() >= 2 && first && !integerOf(t[1]))
        return {labelValue(*first), {checkedName(t[1]), std::nullopt}};
    throw std::invalid_argument(
        "not a label table line (expected VALUE NAME [R G B [A]], ITK-SNAP's IDX R G B A VIS MSH "
        "\"LABEL\", or AAL's ABBREVIATION NAME VALUE)");
}

std::string underscored(std::string name) {
    std::replace_if(
        name.begin(), name.end(),
        [](char c) { return std::isspace(static_cast<unsigned char>(c)); }, '_');
    return name;
}

Rgb colourOf(std::int32_t value, const LabelEntry& entry) {
    return entry.colour ? *entry.colour : categoricalColour(value);
}

}  // namespace

LabelTable readLabelTable(const std::string& path) {
    std::istringstream in(readRegularFile(path, kMaxLabelTableBytes, "a label table"));
    LabelTable table;
    std::map<std::int32_t, int> lineOf;
    std::string line;
    std::vector<bool> quoted;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        // Names typed on Windows may be Latin-1: each line made UTF-8.
        line = utf8FromLegacyText(line);
        if (line.find('\0') != std::string::npos)
            throw InputError(path, lineNo, "a NUL byte: not a text label table");
        try {
            const std::vector<std::string> tokens = tokensOf(line, quoted);
            if (tokens.empty() || tokens[0][0] == '#') continue;
            auto [value, entry] = entryOfLine(tokens, quoted);
            if (const auto seen = lineOf.find(value); seen != lineOf.end())
                throw std::invalid_argument("label " + std::to_string(value) +
                                            " listed again (first at line " +
                                            std::to_string(seen->second) + ")");
            lineOf[value] = lineNo;
            table[value] = std::move(entry);
        } catch (const std::invalid_argument& e) {
            throw InputError(path, lineNo, e.what());
        }
    }
    return table;
}

LabelTable labelTableFromSegmentation(const std::string& path,
                                      const std::vector<std::pair<std::string, std::string>>& keys,
                                      int layer, int layerCount) {
    // Segment index → its fields, from keys "Segment<N>_<Field>".
    std::map<long long, std::map<std::string, std::string>> segments;
    for (const auto& [key, value] : keys) {
        if (key.rfind("Segment", 0) != 0) continue;
        const std::size_t underscore = key.find('_');
        if (underscore == std::string::npos) continue;
        const auto index = integerOf(key.substr(7, underscore - 7));
        if (!index) continue;  // Segmentation_* keys and the like
        segments[*index][key.substr(underscore + 1)] = value;
    }
    LabelTable table;
    for (const auto& [index, segmentFields] : segments) {
        const std::string where = "Segment" + std::to_string(index) + "_";
        // A name for the binding: lambdas may capture bindings only from C++20.
        const std::map<std::string, std::string>& fields = segmentFields;
        const auto field = [&](const char* name) -> std::string {
            const auto it = fields.find(name);
            return it == fields.end() ? std::string() : it->second;
        };
        const auto value = integerOf(field("LabelValue"));
        if (!value || *value < INT32_MIN || *value > INT32_MAX)
            throw InputError(path, 0, where + "LabelValue missing or not an int32");
        const auto segmentLayer = field("Layer").empty() ? 0LL : integerOf(field("Layer"));
        if (!segmentLayer || *segmentLayer < 0 || *segmentLayer >= layerCount)
            throw InputError(path, 0,
                             where + "Layer '" + field("Layer") +
                                 "' is not a layer of the volume (" + std::to_string(layerCount) +
                                 " layer(s))");
        if (*segmentLayer != layer) continue;
        LabelEntry entry;
        entry.name = utf8FromLegacyText(field("Name").empty() ? field("ID") : field("Name"));
        try {
            checkedName(entry.name);
        } catch (const std::invalid_argument& e) {
            throw InputError(path, 0, where + "Name: " + e.what());
        }
        const std::string colour = field("Color");
        if (!colour.empty()) {
            std::istringstream in(colour);
            double c[3];
            if (!(in >> c[0] >> c[1] >> c[2]) || !std::all_of(c, c + 3, [](double x) {
                    return std::isfinite(x) && x >= 0 && x <= 1;
                }))
                throw InputError(path, 0,
                                 where + "Color '" + colour + "' is not 3 numbers in 0..1");
            entry.colour =
                Rgb{std::uint8_t(std::lround(c[0] * 255)), std::uint8_t(std::lround(c[1] * 255)),
                    std::uint8_t(std::lround(c[2] * 255))};
        }
        if (!table.emplace(std::int32_t(*value), std::move(entry)).second)
            throw InputError(path, 0,
                             "two segments with label value " + std::to_string(*value) +
                                 (layerCount > 1 ? " on layer " + std::to_string(layer) : ""));
    }
    return table;
}

std::vector<std::pair<std::string, std::string>> segmentationKeys(
    const LabelTable& table, const std::array<int, 3>& size,
    const std::map<std::int32_t, int>& layerOf) {
    std::vector<std::pair<std::string, std::string>> keys;
    const std::string extent = "0 " + std::to_string(size[0] - 1) + " 0 " +
                               std::to_string(size[1] - 1) + " 0 " + std::to_string(size[2] - 1);
    int index = 0;
    for (const auto& [value, entry] : table) {
        const std::string prefix = "Segment" + std::to_string(index++) + "_";
        const Rgb rgb = colourOf(value, entry);
        std::ostringstream colour;
        colour << rgb[0] / 255.0 << ' ' << rgb[1] / 255.0 << ' ' << rgb[2] / 255.0;
        keys.emplace_back(prefix + "Color", colour.str());
        keys.emplace_back(prefix + "ColorAutoGenerated", "0");
        keys.emplace_back(prefix + "Extent", extent);
        keys.emplace_back(prefix + "ID", "Segment_" + std::to_string(value));
        keys.emplace_back(prefix + "LabelValue", std::to_string(value));
        const auto layer = layerOf.find(value);
        keys.emplace_back(prefix + "Layer",
                          std::to_string(layer == layerOf.end() ? 0 : layer->second));
        keys.emplace_back(prefix + "Name", entry.name);
        keys.emplace_back(prefix + "NameAutoGenerated", "0");
        keys.emplace_back(prefix + "Tags", "|");
    }
    keys.emplace_back("Segmentation_ContainedRepresentationNames", "Binary labelmap|");
    keys.emplace_back("Segmentation_ConversionParameters", "");
    keys.emplace_back("Segmentation_MasterRepresentation", "Binary labelmap");
    keys.emplace_back("Segmentation_ReferenceImageExtentOffset", "0 0 0");
    return keys;
}

void writeLabelTable(const std::string& path, const LabelTable& table) {
    const bool itkSnap = endsWithIgnoringCase(path, ".txt");
    if (!itkSnap && !endsWithIgnoringCase(path, ".ctbl") && !endsWithIgnoringCase(path, ".lut"))
        throw std::invalid_argument("label table '" + path +
                                    "' must end in .txt (ITK-SNAP), .ctbl or .lut");
    writeStreamAtomically(path, [&](std::ostream& out) {
        if (itkSnap) {
            out << "# ITK-SNAP Label Description File (written by dfrecon)\n"
                   "# IDX   -R-  -G-  -B-  -A--  VIS MSH  LABEL\n";
            if (!table.count(0)) out << "    0     0    0    0        0  0  0    \"Clear Label\"\n";
        } else {
            out << "# colour table (written by dfrecon): VALUE NAME R G B A\n";
        }
        for (const auto& [value, entry] : table) {
            const Rgb rgb = colourOf(value, entry);
            if (itkSnap) {
                std::string name = entry.name;
                std::replace(name.begin(), name.end(), '"', '\'');  // the format cannot escape
                out << value << ' ' << int(rgb[0]) << ' ' << int(rgb[1]) << ' ' << int(rgb[2])
                    << " 1 1 1 \"" << name << "\"\n";
            } else {
                out << value << ' ' << underscored(entry.name) << ' ' << int(rgb[0]) << ' '
                    << int(rgb[1]) << ' ' << int(rgb[2]) << " 255\n";
            }
        }
    });
}

std::string labelVolumeStem(const std::string& volumePath) {
    std::string stem = volumePath;
    for (const char* end : {".nii.gz", ".nii", ".nrrd", ".nhdr"})
        if (endsWithIgnoringCase(stem, end)) {
            stem.resize(stem.size() - std::string(end).size());
            break;
        }
    if (endsWithIgnoringCase(stem, ".seg")) stem.resize(stem.size() - 4);
    return stem;
}

std::optional<std::string> labelTableBeside(const std::string& volumePath) {
    const std::string stem = labelVolumeStem(volumePath);
    std::error_code ec;
    for (const char* end : {".txt", ".ctbl", ".lut", "-labels.txt"})
        if (fs::is_regular_file(stem + end, ec)) return stem + end;
    return std::nullopt;
}

}  // namespace dfrecon
