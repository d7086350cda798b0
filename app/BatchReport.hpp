#pragma once
// One table over every record of a batch output folder: a row per ROI (and
// one per entry that failed before its ROIs), the same bytes whether the
// entries ran on one machine or in any number of shards (docs/cluster.md).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace dfrecon::app {

/// The columns, in order: entry (its id), roi, mesh (ID/FILE, empty when
/// not written), volumeCc, contourVolumeCc, validSolid, triangles, seconds,
/// exitCode (0; the failure's code; 4 for a surface that is not a valid
/// closed solid), error.
extern const std::vector<std::string> kBatchReportColumns;

/// Every record under `outputFolder` (FOLDER/ID/record.json; folders
/// starting with '.' are skipped), sorted by manifest position, then id.
/// Throws InputError naming a record that cannot be read or is not a batch
/// record. O(records).
std::vector<nlohmann::json> readBatchRecords(const std::string& outputFolder);

/// The report's rows, one object per row with kBatchReportColumns as keys
/// (null where a value does not apply), in record order and each record's
/// ROI order. `withSeconds` false leaves the seconds column out: the rest
/// does not depend on the machine or the run. O(rows).
nlohmann::ordered_json batchReportRows(const std::vector<nlohmann::json>& records,
                                       bool withSeconds);

/// `rows` as CSV: a header row, then one line per row; numbers as JSON
/// writes them (shortest text that reads back exactly), booleans true or
/// false, null as an empty cell, text quoted where it must be (RFC 4180).
/// `withSeconds` as for batchReportRows. O(rows).
std::string batchReportCsv(const nlohmann::ordered_json& rows, bool withSeconds);

}  // namespace dfrecon::app
