// libFuzzer target for the small text formats around `dfrecon batch`
// (docs/fuzzing.md): batch manifests (app/BatchManifest), batch records
// (app/BatchRecord) and label tables (io/LabelTable). The first byte modulo
// 3 picks the parser (0 manifest, 1 record, 2 label table), the rest is the
// text: one corpus covers all three, and a mutation of that byte hands the
// same text to another parser (a CSV manifest and a plain label list look
// alike; records and JSON manifests are both JSON). The label table reader
// reads files, so its text goes through a temporary .txt file.
//
// Oracles, each what the parser's header promises to the code after it:
// - manifest: InputError, or a non-empty list of entries numbered 1, 2, ...,
//   each with an input and an id that can name a folder (non-empty, at most
//   kMaxStemBytes, not starting with '.', only letters, digits, - _ .),
//   no two ids equal but for case, and the ROI and every option value UTF-8
//   (they go into JSON records and reports);
// - record: parseRecord raises InputError or returns a record whose meshes
//   are plain file names (so a rerun never looks outside the entry's
//   folder), which jsonText writes as UTF-8; decideResume never throws, for
//   any text, and asks only about plain file names;
// - label table: InputError, or names that are non-empty, at most
//   kMaxLabelNameBytes, UTF-8 and free of control bytes, and that
//   writeLabelTable writes and readLabelTable reads back to the same names
//   and colours.
// Any other exception escapes, and libFuzzer reports it as a finding.

#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "app/BatchManifest.hpp"
#include "app/BatchRecord.hpp"
#include "app/Inputs.hpp"
#include "io/Colours.hpp"
#include "io/InputError.hpp"
#include "io/JsonText.hpp"
#include "io/LabelTable.hpp"
#include "io/TextEncoding.hpp"
#include "tests/fuzz/ScratchInput.hpp"

using namespace dfrecon;

namespace {

bool isIdByte(char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
           c == '.' || c == '_' || c == '-';
}

std::string lowerCase(std::string text) {
    for (char& c : text)
        if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
    return text;
}

void fuzzManifest(const std::string& text) {
    std::vector<app::ManifestEntry> entries;
    try {
        entries = app::parseManifest(text, "fuzz-manifest.csv", "/data");
    } catch (const InputError&) {
        return;
    }
    if (entries.empty()) __builtin_trap();
    std::set<std::string> ids;
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const app::ManifestEntry& entry = entries[i];
        if (entry.number != i + 1 || entry.input.empty()) __builtin_trap();
        const std::string& id = entry.id;
        if (id.empty() || id.size() > app::kMaxStemBytes || id[0] == '.') __builtin_trap();
        for (char c : id)
            if (!isIdByte(c)) __builtin_trap();
        if (!ids.insert(lowerCase(id)).second) __builtin_trap();
        if (!isUtf8(entry.roi)) __builtin_trap();
        for (const app::GivenOption& option : entry.options)
            if (!isUtf8(option.value)) __builtin_trap();
    }
}

// What decideResume compares a record with (the options are the defaults,
// as reconstructSettingsJson lists them); the record seeds
// (tests/data/fuzz-batch/record-*) carry the same, so that mutations of
// them reach every step of the rule, up to "unchanged since its record".
const nlohmann::ordered_json& givenInputFiles() {
    static const nlohmann::ordered_json files = app::inputFilesJson(
        {{"rs.dcm", 1024,
          "9f86d081884c7d659a2feaa0c55ad015a3bf4f1b2b0b822cd15d6c15b0f00a08"}});
    return files;
}
const nlohmann::ordered_json& givenOptions() {
    static const nlohmann::ordered_json options{
        {"roi", nullptr},         {"pixel-mm", 0},          {"contour-error", 0},
        {"max-depth", 4},         {"cap", "flat"},          {"interpolation", "smooth"},
        {"smooth-tolerance", 0.05}, {"cap-offset", nullptr}, {"max-error", 0},
        {"allow-invalid", false}, {"ascii", false},         {"format", "ply"}};
    return options;
}
constexpr const char* kGivenVersion = "0.1.0";

void fuzzRecord(const std::string& text) {
    (void)app::decideResume(&text, givenInputFiles(), givenOptions(), kGivenVersion,
                            [](const std::string& mesh) {
                                if (!app::isPlainFileName(mesh)) __builtin_trap();
                                return true;
                            });
    nlohmann::json record;
    try {
        record = app::parseRecord(text, app::kRecordFileName);
    } catch (const InputError&) {
        return;
    }
    if (record.contains("rois") && record["rois"].is_array())
        for (const nlohmann::json& roi : record["rois"])
            if (roi.is_object() && roi.contains("mesh") && roi["mesh"].is_string() &&
                !app::isPlainFileName(roi["mesh"].get<std::string>()))
                __builtin_trap();
    if (!isUtf8(jsonText(record))) __builtin_trap();
}

// The file the label tables read back go to: one per process, next to the
// scratch input (tests/fuzz/ScratchInput.hpp), removed at exit.
const std::string& writtenTablePath() {
    struct Scratch {
        std::string path;
        Scratch() {
            const std::string dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
            path = dir + "/dfrecon-fuzz-batch-written-" + std::to_string(getpid()) + ".txt";
        }
        ~Scratch() { std::remove(path.c_str()); }
    };
    static const Scratch scratch;
    return scratch.path;
}

void fuzzLabelTable(const std::uint8_t* data, std::size_t size) {
    constexpr std::array<const char*, 1> kExtension{{".txt"}};
    const std::string& path = fuzz::writeScratchInput("batch-labels", kExtension, data, size);
    LabelTable table;
    try {
        table = readLabelTable(path);
    } catch (const InputError&) {
        return;
    }
    for (const auto& [value, entry] : table) {
        const std::string& name = entry.name;
        if (name.empty() || name.size() > kMaxLabelNameBytes || !isUtf8(name)) __builtin_trap();
        for (char c : name)
            if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) __builtin_trap();
    }
    // The ITK-SNAP form writeLabelTable writes for .txt: every entry with its
    // colour (a categorical one where the table gives none), and "Clear
    // Label" for 0 where the table has no 0.
    writeLabelTable(writtenTablePath(), table);
    const LabelTable back = readLabelTable(writtenTablePath());
    if (back.size() != table.size() + (table.count(0) ? 0 : 1)) __builtin_trap();
    for (const auto& [value, entry] : back) {
        const auto original = table.find(value);
        if (original == table.end()) {
            if (value != 0 || entry.name != "Clear Label") __builtin_trap();
            continue;
        }
        const Rgb colour = original->second.colour.value_or(categoricalColour(value));
        if (entry.name != original->second.name || entry.colour != colour) __builtin_trap();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
    switch (data[0] % 3) {
        case 0:
            fuzzManifest(text);
            break;
        case 1:
            fuzzRecord(text);
            break;
        default:
            fuzzLabelTable(data, size);
            break;
    }
    return 0;
}
