#include "app/BatchRecord.hpp"

#include "app/ExitCodes.hpp"

namespace dfrecon::app {

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
    const nlohmann::json record = nlohmann::json::parse(recordText, nullptr, false);
    if (record.is_discarded() || !record.is_object() || record.value("format", "") != kRecordFormat)
        return {false, "its record is unreadable"};
    if (!record.value("complete", false))
        return {false, "its record is incomplete (a failure a rerun may not meet again)"};
    if (record.value("version", "") != version)
        return {false, "the program version changed (" + record.value("version", "?") + " -> " +
                           version + ")"};
    if (!record.contains("options") || record["options"] != nlohmann::json::parse(options.dump()))
        return {false, "its options changed"};
    if (!record.contains("inputFiles") ||
        record["inputFiles"] != nlohmann::json::parse(inputFiles.dump()))
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
