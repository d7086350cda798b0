#include "app/BatchRecord.hpp"

#include "contours/InputError.hpp"
#include "report/ExitCodes.hpp"

namespace dfrecon::app {

JsonLimits recordJsonLimits() {
    JsonLimits limits;
    limits.maxDepth = 16;
    limits.maxBytes = std::uint64_t(256) << 20;
    return limits;
}

bool isPlainFileName(const std::string& name) {
    return !name.empty() && name != "." && name != ".." &&
           name.find_first_of(std::string("/\\\0", 3)) == std::string::npos;
}

nlohmann::json parseRecord(const std::string& text, const std::string& file) {
    nlohmann::json record = parseJsonText(text, file, recordJsonLimits());
    if (!record.is_object() || !record.contains("format") || record["format"] != kRecordFormat ||
        !record.contains("id") || !record["id"].is_string() || !record.contains("entry") ||
        !record["entry"].is_number_unsigned())
        throw InputError(file, 0, std::string("not a batch record (") + kRecordFormat + ")");
    if (record.contains("rois") && record["rois"].is_array())
        for (std::size_t r = 0; r < record["rois"].size(); ++r) {
            const nlohmann::json& roi = record["rois"][r];
            if (!roi.is_object() || !roi.contains("mesh") || roi["mesh"].is_null()) continue;
            if (!roi["mesh"].is_string() || !isPlainFileName(roi["mesh"].get<std::string>()))
                throw InputError(file, 0,
                                 "/rois/" + std::to_string(r) +
                                     "/mesh is not the name of a file in the entry's folder");
        }
    return record;
}

nlohmann::ordered_json inputFilesJson(const std::vector<InputFile>& files) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const InputFile& file : files)
        list.push_back({{"path", file.path}, {"bytes", file.bytes}, {"sha256", file.sha256}});
    return list;
}

bool isLastingFailure(int exitCode) {
    return exitCode != kExitRuntime;
}

namespace {

ResumeDecision decide(const std::string& recordText, const nlohmann::ordered_json& inputFiles,
                      const nlohmann::ordered_json& options, const std::string& version,
                      const std::function<bool(const std::string&)>& meshExists) {
    // Compared as plain JSON: object keys unordered, 1 and 1.0 alike.
    nlohmann::json record;
    try {
        record = parseRecord(recordText, kRecordFileName);
    } catch (const InputError& e) {
        return {false, "its record is unreadable (" + e.problem() + ")"};
    }
    if (!record.value("complete", false))
        return {false, "its record is incomplete (a failure a rerun may not meet again)"};
    if (record.value("version", "") != version)
        return {false, "the program version changed (" + record.value("version", "?") + " -> " +
                           version + ")"};
    if (!record.contains("options") ||
        record["options"] != nlohmann::json::parse(jsonText(options)))
        return {false, "its options changed"};
    if (!record.contains("inputFiles") ||
        record["inputFiles"] != nlohmann::json::parse(jsonText(inputFiles)))
        return {false, "its input changed"};
    if (record.contains("rois") && record["rois"].is_array())
        for (const nlohmann::json& roi : record["rois"])
            if (roi.is_object() && roi.contains("mesh") && roi["mesh"].is_string() &&
                !meshExists(roi["mesh"].get<std::string>()))
                return {false, "its mesh " + roi["mesh"].get<std::string>() + " is missing"};
    return {true, "unchanged since its record"};
}

}  // namespace

ResumeDecision decideResume(const std::string* recordText, const nlohmann::ordered_json& inputFiles,
                            const nlohmann::ordered_json& options, const std::string& version,
                            const std::function<bool(const std::string&)>& meshExists) {
    if (!recordText) return {false, "no record yet"};
    try {
        return decide(*recordText, inputFiles, options, version, meshExists);
    } catch (const nlohmann::json::exception&) {
        return {false, "its record is unreadable"};  // a value of the wrong type
    }
}

}  // namespace dfrecon::app
