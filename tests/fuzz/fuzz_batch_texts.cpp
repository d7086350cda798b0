// libFuzzer target for the small text formats around `dfrecon batch`
// (docs/fuzzing.md): batch manifests (app/BatchManifest), batch records
// (app/BatchRecord) and label tables (io/labels/LabelTable). The first byte modulo
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

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "app/BatchManifest.hpp"
#include "app/BatchRecord.hpp"
#include "app/Inputs.hpp"
#include "contours/InputError.hpp"
#include "io/files/JsonText.hpp"
#include "io/files/TextEncoding.hpp"
#include "io/images/Colours.hpp"
#include "io/labels/LabelTable.hpp"
#include "tests/fuzz/ScratchInput.hpp"

using namespace dfrecon;

namespace {

// Traps with the oracle that failed named on stderr: the traps of one
// function share an address, so the stack alone does not tell them apart.
void expect(bool holds, const char* oracle) {
    if (holds) return;
    std::fprintf(stderr, "fuzz_batch_texts: oracle failed: %s\n", oracle);
    __builtin_trap();
}

bool isIdByte(char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' ||
           c == '_' || c == '-';
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
    expect(!entries.empty(), "manifest: no entries");
    std::set<std::string> ids;
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const app::ManifestEntry& entry = entries[i];
        expect(entry.number == i + 1, "manifest: entries numbered 1, 2, ...");
        expect(!entry.input.empty(), "manifest: an entry without input");
        const std::string& id = entry.id;
        expect(!id.empty() && id.size() <= app::kMaxStemBytes && id[0] != '.',
               "manifest: an id that is empty, too long or starts with '.'");
        for (char c : id) expect(isIdByte(c), "manifest: an id byte other than [A-Za-z0-9._-]");
        expect(ids.insert(lowerCase(id)).second, "manifest: two ids equal but for case");
        expect(isUtf8(entry.roi), "manifest: a ROI that is not UTF-8");
        for (const app::GivenOption& option : entry.options)
            expect(isUtf8(option.value), "manifest: an option value that is not UTF-8");
    }
}

// What decideResume compares a record with (the options are the defaults,
// as reconstructSettingsJson lists them); the record seeds
// (tests/data/fuzz-batch/record-*) carry the same, so that mutations of
// them reach every step of the rule, up to "unchanged since its record".
const nlohmann::ordered_json& givenInputFiles() {
    static const nlohmann::ordered_json files = app::inputFilesJson(
        {{"rs.dcm", 1024, "9f86d081884c7d659a2feaa0c55ad015a3bf4f1b2b0b822cd15d6c15b0f00a08"}});
    return files;
}
const nlohmann::ordered_json& givenOptions() {
    static const nlohmann::ordered_json options{
        {"roi", nullptr},           {"pixel-mm", 0},         {"contour-error", 0},
        {"max-depth", 4},           {"cap", "flat"},         {"interpolation", "smooth"},
        {"smooth-tolerance", 0.05}, {"cap-offset", nullptr}, {"max-error", 0},
        {"allow-invalid", false},   {"ascii", false},        {"format", "ply"}};
    return options;
}
constexpr const char* kGivenVersion = "0.1.0";

void fuzzRecord(const std::string& text) {
    (void)app::decideResume(&text, givenInputFiles(), givenOptions(), kGivenVersion,
                            [](const std::string& mesh) {
                                expect(app::isPlainFileName(mesh),
                                       "record: decideResume asks about a mesh that is no "
                                       "plain file name");
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
            if (roi.is_object() && roi.contains("mesh") && roi["mesh"].is_string())
                expect(app::isPlainFileName(roi["mesh"].get<std::string>()),
                       "record: a mesh that is no plain file name");
    expect(isUtf8(jsonText(record)), "record: jsonText of it is not UTF-8");
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
        expect(!name.empty() && name.size() <= kMaxLabelNameBytes,
               "label table: a name that is empty or too long");
        expect(isUtf8(name), "label table: a name that is not UTF-8");
        for (char c : name)
            expect(static_cast<unsigned char>(c) >= 0x20 && c != 0x7F,
                   "label table: a control byte in a name");
    }
    // The ITK-SNAP form writeLabelTable writes for .txt: every entry with its
    // colour (a categorical one where the table gives none), and "Clear
    // Label" for 0 where the table has no 0.
    writeLabelTable(writtenTablePath(), table);
    const LabelTable back = readLabelTable(writtenTablePath());
    expect(back.size() == table.size() + (table.count(0) ? 0 : 1),
           "label table: read back with other values");
    for (const auto& [value, entry] : back) {
        const auto original = table.find(value);
        if (original == table.end()) {
            expect(value == 0 && entry.name == "Clear Label",
                   "label table: read back with other values");
            continue;
        }
        const Rgb colour = original->second.colour.value_or(categoricalColour(value));
        // ITK-SNAP's quoted labels cannot hold a quote: the writer puts an
        // apostrophe there (docs/formats.md), the one change it makes.
        std::string written = original->second.name;
        std::replace(written.begin(), written.end(), '"', '\'');
        expect(entry.name == written, "label table: a name reads back changed");
        expect(entry.colour == colour, "label table: a colour reads back changed");
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
