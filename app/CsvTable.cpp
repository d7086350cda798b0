#include "app/CsvTable.hpp"

#include "io/files/JsonText.hpp"

namespace dfrecon::app {

namespace {

std::string csvCell(const nlohmann::ordered_json& value) {
    if (value.is_null()) return "";
    const std::string text = value.is_string() ? value.get<std::string>() : jsonText(value);
    if (text.find_first_of(",\"\r\n") == std::string::npos &&
        (text.empty() || (text.front() != ' ' && text.back() != ' ')))
        return text;
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

}  // namespace

std::string csvTable(const nlohmann::ordered_json& rows, const std::vector<std::string>& columns) {
    std::string csv;
    for (std::size_t c = 0; c < columns.size(); ++c) csv += (c ? "," : "") + columns[c];
    csv += "\n";
    for (const nlohmann::ordered_json& r : rows) {
        for (std::size_t c = 0; c < columns.size(); ++c)
            csv += (c ? "," : "") + csvCell(r.contains(columns[c]) ? r[columns[c]] : nullptr);
        csv += "\n";
    }
    return csv;
}

}  // namespace dfrecon::app
