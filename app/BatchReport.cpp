#include "app/BatchReport.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/BatchRecord.hpp"
#include "app/CsvTable.hpp"
#include "contours/InputError.hpp"
#include "io/files/JsonText.hpp"
#include "io/files/RegularFile.hpp"
#include "report/ExitCodes.hpp"

namespace dfrecon::app {

namespace fs = std::filesystem;

const std::vector<std::string> kBatchReportColumns{
    "entry",      "roi",       "mesh",    "volumeCc", "contourVolumeCc",
    "validSolid", "triangles", "seconds", "exitCode", "error"};

std::vector<nlohmann::json> readBatchRecords(const std::string& outputFolder) {
    std::vector<nlohmann::json> records;
    std::error_code error;
    for (fs::directory_iterator it(outputFolder, error), end; !error && it != end;
         it.increment(error)) {
        const std::string name = it->path().filename().string();
        if (name.empty() || name[0] == '.' || !it->is_directory(error)) continue;
        const fs::path file = it->path() / kRecordFileName;
        if (!fs::exists(fs::symlink_status(file, error))) continue;
        const std::string text =
            readRegularFile(file.string(), recordJsonLimits().maxBytes, "a batch record");
        records.push_back(parseRecord(text, file.string()));
    }
    if (error) throw InputError(outputFolder, 0, "cannot list folder: " + error.message());
    std::sort(records.begin(), records.end(), [](const nlohmann::json& a, const nlohmann::json& b) {
        const auto ka = a["entry"].get<std::size_t>(), kb = b["entry"].get<std::size_t>();
        return ka != kb ? ka < kb : a["id"].get<std::string>() < b["id"].get<std::string>();
    });
    return records;
}

namespace {

// `object[key]` when it has it, else null.
nlohmann::ordered_json field(const nlohmann::json& object, const char* key) {
    if (!object.is_object() || !object.contains(key)) return nullptr;
    return nlohmann::ordered_json::parse(jsonText(object[key]));
}

nlohmann::ordered_json row(const nlohmann::json& record, const nlohmann::json* roi,
                           bool withSeconds) {
    nlohmann::ordered_json out;
    const std::string id = record["id"].get<std::string>();
    out["entry"] = id;
    if (!roi) {
        for (const char* key :
             {"roi", "mesh", "volumeCc", "contourVolumeCc", "validSolid", "triangles"})
            out[key] = nullptr;
        if (withSeconds) out["seconds"] = field(record, "seconds");
        out["exitCode"] = field(record, "exitCode");
        out["error"] = field(record, "error");
        return out;
    }
    out["roi"] = field(*roi, "roi");
    const nlohmann::ordered_json mesh = field(*roi, "mesh");
    out["mesh"] = mesh.is_string() ? nlohmann::ordered_json(id + "/" + mesh.get<std::string>())
                                   : nlohmann::ordered_json(nullptr);
    out["volumeCc"] = field(*roi, "volumeCc");
    out["contourVolumeCc"] = field(*roi, "contourVolumeCc");
    out["validSolid"] = field(*roi, "validSolid");
    out["triangles"] = field(*roi, "triangles");
    if (withSeconds) out["seconds"] = field(roi->value("seconds", nlohmann::json()), "total");
    const nlohmann::ordered_json failure = field(*roi, "exitCode");
    const bool invalid = !failure.is_number() && out["validSolid"] == false;
    out["exitCode"] = failure.is_number() ? failure : nlohmann::ordered_json(invalid ? 4 : 0);
    out["error"] = failure.is_number() ? field(*roi, "error")
                   : invalid           ? nlohmann::ordered_json("not a valid closed solid")
                                       : nlohmann::ordered_json(nullptr);
    return out;
}

}  // namespace

nlohmann::ordered_json batchReportRows(const std::vector<nlohmann::json>& records,
                                       bool withSeconds) {
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const nlohmann::json& record : records) {
        const bool entryFailed = record.contains("error") && !record["error"].is_null();
        if (entryFailed || !record.contains("rois") || !record["rois"].is_array()) {
            rows.push_back(row(record, nullptr, withSeconds));
            continue;
        }
        for (const nlohmann::json& roi : record["rois"])
            rows.push_back(row(record, &roi, withSeconds));
    }
    return rows;
}

std::string batchReportCsv(const nlohmann::ordered_json& rows, bool withSeconds) {
    std::vector<std::string> columns;
    for (const std::string& column : kBatchReportColumns)
        if (withSeconds || column != "seconds") columns.push_back(column);
    return csvTable(rows, columns);
}

}  // namespace dfrecon::app
