#pragma once
// One manifest entry of `dfrecon batch`, run or skipped: its input read,
// every chosen ROI reconstructed into the entry's folder (app/RoiReconstruction,
// as `reconstruct --all` does), and its record written last (app/BatchRecord).
#include <string>

#include "app/BatchManifest.hpp"
#include "app/Commands.hpp"
#include "cl/Runtime.hpp"
#include "report/ReconstructSettings.hpp"

namespace dfrecon::app {

struct EntryOutcome {
    enum class Status { Done, Skipped, Failed } status = Status::Done;
    int exitCode = 0;     // 0; the first failure's code; 4 for a surface that is not valid
    std::string summary;  // one line for stdout, without the id
    std::string error;    // the failure's message for stderr, or ""
    double seconds = 0;
};

/// "done", "skipped" or "failed", as reports and worker answers name a
/// status; and back (anything else is "failed"). O(1).
const char* entryStatusName(EntryOutcome::Status status);
EntryOutcome::Status entryStatusNamed(const std::string& name);

/// Runs `entry` into OUTPUT/ID/ with `base` changed by the entry's options,
/// unless its record says it is done with the same input bytes, options and
/// `version` (decideResume), in which case the outcome is the record's. One
/// failing ROI never stops the others; a failure of the entry (its input,
/// its ROI choice, its folder, its record) is its outcome, never thrown.
/// The old record is removed before the entry runs again, so no record ever
/// describes meshes being rewritten. Uses `runtime` only, so entries may run
/// at once with a runtime each. O(the entry's reconstructions + input bytes).
EntryOutcome runBatchEntry(ocl::Runtime& runtime, const ManifestEntry& entry,
                           const ReconstructSettings& base, const std::string& outputFolder,
                           const std::string& version);

/// Writes OUTPUT/ID/record.json for an entry that failed outside
/// runBatchEntry (its worker process died): the entry, options and input
/// files as runBatchEntry would record them, no ROIs, and the failure's
/// `error` with its `exitCode`. `lasting` marks it complete, so that a rerun with the same
/// input, options and version skips it instead of meeting the failure
/// again. Throws on a folder or record that cannot be written.
struct EntryFailure {
    std::string error;
    int exitCode = 0;
    bool lasting = false;  // complete: a rerun skips it
};
void writeFailedEntryRecord(const ManifestEntry& entry, const ReconstructSettings& base,
                            const std::string& outputFolder, const std::string& version,
                            const EntryFailure& failure);

}  // namespace dfrecon::app
