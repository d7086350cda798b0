#include "app/BatchManifest.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "app/Inputs.hpp"
#include "contours/InputError.hpp"
#include "io/files/JsonText.hpp"
#include "io/files/RegularFile.hpp"
#include "io/files/TextEncoding.hpp"

namespace dfrecon::app {

namespace fs = std::filesystem;

namespace {

// A manifest value with the place it came from: CSV line and column, or the
// JSON entry (line 0) and key.
struct Field {
    std::string key, value;
    int line = 0;
    std::string where;  // "cell C (KEY)" or "entry N, key 'K'"
};

const std::vector<std::string> kEntryKeys{"input", "id", "roi"};

// Names of the reports `batch-report` writes into the output folder: no
// entry's folder may take them.
const std::vector<std::string> kReservedIds{"batch-report.csv", "batch-report.json"};

const std::vector<std::string>& optionKeys() {
    static const std::vector<std::string> names = reconstructSettingsNames();
    return names;
}

std::string knownKeys() {
    std::string all;
    for (const std::string& key : kEntryKeys) all += (all.empty() ? "" : ", ") + key;
    for (const std::string& key : optionKeys()) all += ", " + key;
    return all;
}

bool isKnownKey(const std::string& key) {
    const std::vector<std::string>& options = optionKeys();
    return std::count(kEntryKeys.begin(), kEntryKeys.end(), key) ||
           std::count(options.begin(), options.end(), key);
}

std::string lowerCase(std::string text) {
    for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

// Why `id` cannot name a folder, or "".
std::string idProblem(const std::string& id) {
    if (id.empty()) return "an empty id";
    if (id.size() > kMaxStemBytes)
        return "an id longer than " + std::to_string(kMaxStemBytes) + " bytes";
    if (id[0] == '.') return "an id starting with '.'";
    for (char c : id)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.')
            return "an id with a character other than letters, digits, - _ .";
    if (std::count(kReservedIds.begin(), kReservedIds.end(), lowerCase(id)))
        return "the id '" + id + "', the name of a report batch-report writes";
    return "";
}

// One entry from its fields (each key at most once, every key known).
ManifestEntry makeEntry(std::size_t number, const std::vector<Field>& fields,
                        const std::string& file, int line, const std::string& folder) {
    ManifestEntry entry;
    entry.number = number;
    entry.id = std::to_string(number);
    entry.line = line;
    entry.where =
        line > 0 ? file + ":" + std::to_string(line) : file + ": entry " + std::to_string(number);
    auto fail = [&](const Field& field, const std::string& problem) {
        throw InputError(file, field.line, field.where + ": " + problem);
    };
    for (const Field& field : fields) {
        if (field.value.size() > kMaxManifestValueBytes)
            fail(field, "a value longer than " + std::to_string(kMaxManifestValueBytes) + " bytes");
        if (field.key == "input") {
            if (field.value.empty()) fail(field, "an empty input");
            entry.input = field.value;
        } else if (field.key == "id") {
            const std::string problem = idProblem(field.value);
            if (!problem.empty()) fail(field, problem);
            entry.id = field.value;
        } else if (field.key == "roi") {
            entry.roi = field.value;
        } else {
            // Checked now, by the command line's own definitions.
            entry.options.push_back({field.key, field.value, field.where});
            try {
                withGivenOptions(ReconstructSettings{}, {entry.options.back()});
            } catch (const std::invalid_argument& e) {
                throw InputError(file, field.line, e.what());
            }
        }
    }
    if (entry.input.empty())
        throw InputError(file, line,
                         (line > 0 ? "" : "entry " + std::to_string(number) + ": ") + "no input");
    const fs::path input(entry.input);
    entry.inputPath = input.is_absolute() ? input.string() : (fs::path(folder) / input).string();
    return entry;
}

// ---- CSV ----------------------------------------------------------------

struct Cell {
    std::string text;
    int line = 0, column = 0;
    bool quoted = false;
};

class CsvReader {
  public:
    CsvReader(const std::string& text, const std::string& file) : text_(text), file_(file) {
        if (text_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = 3;
    }

    bool done() const { return pos_ >= text_.size(); }

    /// The next row's cells; false at the end.
    bool nextRow(std::vector<Cell>& row) {
        row.clear();
        if (done()) return false;
        for (;;) {
            row.push_back(cell());
            if (row.size() > kMaxManifestColumns)
                fail(row.back(), "more than " + std::to_string(kMaxManifestColumns) + " cells");
            if (done()) return true;
            const char c = text_[pos_];
            if (c == ',') {
                advance();
                continue;
            }
            lineEnd();
            return true;
        }
    }

    [[noreturn]] void fail(const Cell& at, const std::string& problem) const {
        throw InputError(file_, at.line, "column " + std::to_string(at.column) + ": " + problem);
    }

  private:
    void advance() {
        if (text_[pos_] == '\0') {
            Cell here{"", line_, column_, false};
            fail(here, "a NUL byte (a manifest is text)");
        }
        if (text_[pos_] == '\n') {
            ++line_;
            column_ = 1;
        } else {
            ++column_;
        }
        ++pos_;
    }
    bool atLineEnd() const { return text_[pos_] == '\n' || text_[pos_] == '\r'; }
    void lineEnd() {
        if (text_[pos_] == '\r') {
            ++pos_;  // CR LF, or a lone CR, ends the line
            if (pos_ < text_.size() && text_[pos_] == '\n') ++pos_;
            ++line_;
            column_ = 1;
        } else {
            advance();
        }
    }
    void skipBlanks() {
        while (!done() && (text_[pos_] == ' ' || text_[pos_] == '\t')) advance();
    }
    Cell cell() {
        skipBlanks();
        Cell cell{"", line_, column_, false};
        if (!done() && text_[pos_] == '"') {
            cell.quoted = true;
            advance();
            for (;;) {
                if (done()) fail(cell, "a quoted cell that is never closed");
                if (text_[pos_] == '"') {
                    advance();
                    if (done() || text_[pos_] != '"') break;
                }
                if (text_[pos_] == '\r' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '\n') {
                    ++pos_;  // CR LF inside a quoted cell is one line break
                    continue;
                }
                cell.text += text_[pos_];
                advance();
                if (cell.text.size() > kMaxManifestValueBytes)
                    fail(cell, "a value longer than " + std::to_string(kMaxManifestValueBytes) +
                                   " bytes");
            }
            skipBlanks();
            if (!done() && text_[pos_] != ',' && !atLineEnd())
                fail(Cell{"", line_, column_, false},
                     "text after a closing quote (a quote inside a cell is written \"\")");
            return cell;
        }
        while (!done() && text_[pos_] != ',' && !atLineEnd()) {
            if (text_[pos_] == '"')
                fail(Cell{"", line_, column_, false},
                     "a quote inside an unquoted cell (quote the whole cell and double the "
                     "quote)");
            cell.text += text_[pos_];
            advance();
            if (cell.text.size() > kMaxManifestValueBytes)
                fail(cell,
                     "a value longer than " + std::to_string(kMaxManifestValueBytes) + " bytes");
        }
        while (!cell.text.empty() && (cell.text.back() == ' ' || cell.text.back() == '\t'))
            cell.text.pop_back();
        return cell;
    }

    const std::string& text_;
    std::string file_;
    std::size_t pos_ = 0;
    int line_ = 1, column_ = 1;
};

bool isBlankRow(const std::vector<Cell>& row) {
    return row.size() == 1 && !row[0].quoted && row[0].text.empty();
}

std::vector<ManifestEntry> parseCsv(const std::string& text, const std::string& file,
                                    const std::string& folder) {
    CsvReader reader(text, file);
    std::vector<Cell> header, row;
    while (reader.nextRow(header) && isBlankRow(header)) {
    }
    if (header.empty() || isBlankRow(header))
        throw InputError(file, 0, "no header row (the first line names the columns: input, ...)");
    std::vector<std::string> keys;
    for (const Cell& cell : header) {
        if (!isKnownKey(cell.text))
            reader.fail(cell, "unknown key '" + cell.text + "' (keys: " + knownKeys() + ")");
        if (std::count(keys.begin(), keys.end(), cell.text))
            reader.fail(cell, "the key '" + cell.text + "' a second time");
        keys.push_back(cell.text);
    }
    if (!std::count(keys.begin(), keys.end(), "input"))
        throw InputError(file, header[0].line, "no 'input' column (keys: " + knownKeys() + ")");
    std::vector<ManifestEntry> entries;
    while (reader.nextRow(row)) {
        if (isBlankRow(row)) continue;
        if (row.size() != keys.size())
            reader.fail(row.size() > keys.size() ? row[keys.size()] : row.back(),
                        std::to_string(row.size()) + " cells where the header has " +
                            std::to_string(keys.size()));
        if (entries.size() == kMaxManifestEntries)
            reader.fail(row[0], "more than " + std::to_string(kMaxManifestEntries) + " entries");
        std::vector<Field> fields;
        for (std::size_t c = 0; c < row.size(); ++c)
            if (!row[c].text.empty())  // an empty cell: the default
                fields.push_back(
                    {keys[c], keys[c] == "input" ? row[c].text : utf8FromLegacyText(row[c].text),
                     row[c].line, "cell " + std::to_string(c + 1) + " (" + keys[c] + ")"});
        entries.push_back(makeEntry(entries.size() + 1, fields, file, row[0].line, folder));
    }
    return entries;
}

// ---- JSON ---------------------------------------------------------------

std::vector<ManifestEntry> parseJson(const std::string& text, const std::string& file,
                                     const std::string& folder) {
    // Deeper than list, object, value is no manifest: the parser stops
    // there, before it builds what a hostile file nests.
    JsonLimits limits;
    limits.maxDepth = 2;
    const nlohmann::json list = parseJsonText(text, file, limits);
    if (!list.is_array())
        throw InputError(file, 0, "a JSON manifest is a list of objects, one per entry");
    if (list.size() > kMaxManifestEntries)
        throw InputError(file, 0, "more than " + std::to_string(kMaxManifestEntries) + " entries");
    std::vector<ManifestEntry> entries;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string entryName = "entry " + std::to_string(i + 1);
        if (!list[i].is_object()) throw InputError(file, 0, entryName + ": not an object");
        std::vector<Field> fields;
        for (const auto& [key, value] : list[i].items()) {
            const std::string where = entryName + ", key '" + key + "'";
            if (!isKnownKey(key))
                throw InputError(file, 0, where + ": unknown key (keys: " + knownKeys() + ")");
            std::string textValue;
            if (value.is_null()) continue;  // the default
            if (value.is_string())
                textValue = value.get<std::string>();
            else if (value.is_boolean())
                textValue = value.get<bool>() ? "true" : "false";
            else if (value.is_number())
                textValue = value.dump();
            else
                throw InputError(file, 0,
                                 where + ": a value that is no string, number, boolean or null");
            fields.push_back({key, textValue, 0, where});
        }
        entries.push_back(makeEntry(i + 1, fields, file, 0, folder));
    }
    return entries;
}

}  // namespace

std::vector<ManifestEntry> parseManifest(const std::string& text, const std::string& file,
                                         const std::string& folder) {
    const std::size_t bom = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
    const std::size_t start = text.find_first_not_of(" \t\r\n", bom);
    const bool json = start != std::string::npos && text[start] == '[';
    // Text typed on Windows may be Latin-1. JSON must be UTF-8 to parse,
    // so its lines are made so (io/files/JsonText); CSV cells are made so one by
    // one, all but the input's path, which names a file by its bytes.
    std::vector<ManifestEntry> entries =
        json ? parseJson(text.substr(bom), file, folder) : parseCsv(text, file, folder);
    // Entries become folders, and folders may not tell case apart.
    std::map<std::string, const ManifestEntry*> byId;
    for (const ManifestEntry& entry : entries) {
        const auto [it, fresh] = byId.emplace(lowerCase(entry.id), &entry);
        if (fresh) continue;
        const ManifestEntry& first = *it->second;
        throw InputError(file, entry.line,
                         (entry.line > 0 ? "" : "entry " + std::to_string(entry.number) + ": ") +
                             "the id '" + entry.id + "' is already " +
                             (first.line > 0 ? "line " + std::to_string(first.line)
                                             : "entry " + std::to_string(first.number)) +
                             "'s" + (first.id == entry.id ? "" : " ('" + first.id + "')") +
                             " (ids name folders, so they must differ in more than case)");
    }
    if (entries.empty()) throw InputError(file, 0, "no entries");
    return entries;
}

std::vector<ManifestEntry> readManifest(const std::string& path) {
    const std::string text = readRegularFile(path, kMaxManifestBytes, "a batch manifest");
    const fs::path parent = fs::path(path).parent_path();
    return parseManifest(text, path, parent.empty() ? "." : parent.string());
}

}  // namespace dfrecon::app
