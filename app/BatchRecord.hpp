#pragma once
// The record a batch entry leaves in its folder (OUT/ID/record.json), and
// the rule that lets a rerun skip it: the record exists, is complete, and
// was made from the same input bytes, options and program version
// (docs/cli.md, "dfrecon batch"). Records are written last and atomically,
// so a task killed midway leaves none for the entry it was doing.
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/contours/InputDigest.hpp"
#include "io/files/JsonText.hpp"

namespace dfrecon::app {

inline constexpr const char* kRecordFileName = "record.json";
inline constexpr const char* kRecordFormat = "dfrecon-batch-record 1";

/// How a record is read: a regular file of at most 256 MiB (a structure set
/// of 10 000 ROIs takes some 20 MB), JSON at most 16 levels deep (records
/// nest 5). io/files/JsonText.
JsonLimits recordJsonLimits();

/// Parses a record's text (record.json in `file`); InputError naming the
/// file as io/files/JsonText reports it, or when it is not an object of
/// kRecordFormat with a string id, an entry number and, for every ROI with a
/// mesh, a mesh that is a plain file name (isPlainFileName): a record
/// pointing outside its entry folder is not trusted. O(record size).
nlohmann::json parseRecord(const std::string& text, const std::string& file);

/// Whether `name` names a file in the folder it is relative to: one path
/// component, neither "." nor "..", without '/', '\\' or NUL. O(name).
bool isPlainFileName(const std::string& name);

/// The input's files as [{path, bytes, sha256}], the form records keep. O(files).
nlohmann::ordered_json inputFilesJson(const std::vector<InputFile>& files);

/// A failure a rerun may not meet again (exit 3: device, memory, a full
/// disk) leaves its entry incomplete; bad input (2), a usage problem such as
/// an unknown ROI (1) and an invalid solid (4) follow from the input and
/// options, so they are results like any other. O(1).
bool isLastingFailure(int exitCode);

struct ResumeDecision {
    bool skip = false;
    std::string reason;  // why it runs (or "unchanged since its record")
};

/// Whether an entry whose folder holds `recordText` (nullptr: no record)
/// can be skipped: the record parses (parseRecord), is complete, its
/// version, options and inputFiles equal the ones given (as JSON values:
/// key order and number spelling aside), and every mesh it lists (rois[].mesh,
/// relative to the entry's folder) exists by `meshExists`. O(record size).
ResumeDecision decideResume(const std::string* recordText, const nlohmann::ordered_json& inputFiles,
                            const nlohmann::ordered_json& options, const std::string& version,
                            const std::function<bool(const std::string&)>& meshExists);

}  // namespace dfrecon::app
