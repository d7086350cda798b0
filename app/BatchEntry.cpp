#include "app/BatchEntry.hpp"

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "api/Stopwatch.hpp"
#include "app/BatchRecord.hpp"
#include "app/Inputs.hpp"
#include "app/RoiReconstruction.hpp"
#include "contours/InputError.hpp"
#include "io/contours/InputDigest.hpp"
#include "io/files/AtomicWrite.hpp"
#include "io/files/JsonText.hpp"
#include "io/files/RegularFile.hpp"
#include "report/ExitCodes.hpp"
#include "report/Failure.hpp"
#include "report/Reports.hpp"

namespace dfrecon::app {

namespace fs = std::filesystem;

namespace {

// The record in an entry's folder: none when there is nothing by its name;
// "" (unreadable, so the entry runs again and replaces it) when it is no
// regular file of a record's size: a named pipe there must not block the
// batch, a link to /dev/zero must not fill its memory.
std::optional<std::string> readRecordText(const fs::path& path) {
    std::error_code error;
    if (!fs::exists(fs::symlink_status(path, error))) return std::nullopt;
    try {
        return readRegularFile(path.string(), recordJsonLimits().maxBytes, "a batch record");
    } catch (const InputError&) {
        return std::string();
    }
}

// The outcome a record describes, for an entry skipped because of it.
EntryOutcome outcomeOfRecord(const std::string& recordText) {
    EntryOutcome outcome;
    outcome.status = EntryOutcome::Status::Skipped;
    std::string summary = "done";
    try {
        const nlohmann::json record = parseRecord(recordText, kRecordFileName);
        outcome.exitCode = record.value("exitCode", 0);
        summary = record.value("summary", summary);
    } catch (const std::exception&) {
        // decideResume read it; a value of an odd type here is only not shown
    }
    if (outcome.exitCode != 0) outcome.error = summary;
    outcome.summary = "skipped, unchanged since its record (" + summary + ")";
    return outcome;
}

struct RoiTally {
    nlohmann::ordered_json reports = nlohmann::ordered_json::array();  // per ROI, in order
    std::size_t rois = 0, done = 0;
    std::string failed, invalid;  // names, comma-separated
    std::string firstError;
    int firstFailure = 0;
    bool lasting = true;  // no failure a rerun may not meet again
};

// Every ROI of `rois` into FOLDER/STEM.EXT (the folder format), one after the other on
// `runtime`; one that fails is reported and the others go on.
RoiTally reconstructRois(ocl::Runtime& runtime, const std::vector<const Roi*>& rois,
                         const ContourInput& input, const ReconstructSettings& settings,
                         const fs::path& folder) {
    // Nothing on stderr: the record says it all.
    const RoiWriteOptions quiet{true, false, false};
    RoiTally tally;
    tally.rois = rois.size();
    const std::vector<std::string> stems = uniqueFileStems(rois);
    for (std::size_t i = 0; i < rois.size(); ++i) {
        const Stopwatch watch;
        const std::string mesh = stems[i] + meshFormatExtension(settings.folderFormat());
        // A mesh of an earlier run must not pass for this run's.
        std::error_code ignored;
        fs::remove(folder / mesh, ignored);
        RoiOutcome roi;
        try {
            if (rois[i]->defect) throw *rois[i]->defect;
            roi = writeRoiSurface(runtime, *rois[i],
                                  MeshOutput{(folder / mesh).string(), settings.folderFormat()},
                                  input, settings, quiet);
        } catch (...) {
            roi = failedRoi(*rois[i], std::current_exception());
        }
        roi.report["mesh"] = roi.report.value("written", false) ? nlohmann::ordered_json(mesh)
                                                                : nlohmann::ordered_json(nullptr);
        roi.report["seconds"]["total"] = watch.total();
        const std::string& name = rois[i]->name;
        if (roi.failure != 0) {
            tally.failed += (tally.failed.empty() ? "" : ", ") + name;
            if (tally.firstFailure == 0) {
                tally.firstFailure = roi.failure;
                tally.firstError =
                    "ROI '" + name + "': " + roi.report.value("error", std::string());
            }
            tally.lasting = tally.lasting && isLastingFailure(roi.failure);
        } else {
            ++tally.done;
            if (roi.invalid) tally.invalid += (tally.invalid.empty() ? "" : ", ") + name;
        }
        tally.reports.push_back(std::move(roi.report));
    }
    return tally;
}

// The outcome of an entry that ran: its own failure if it had one, else its ROIs'.
EntryOutcome outcomeOf(const std::optional<Failure>& entryFailure, const RoiTally& tally) {
    EntryOutcome outcome;
    if (entryFailure) {
        outcome.status = EntryOutcome::Status::Failed;
        outcome.exitCode = entryFailure->exitCode;
        outcome.error = entryFailure->message;
        outcome.summary = "failed: " + entryFailure->message;
    } else if (tally.firstFailure != 0) {
        outcome.status = EntryOutcome::Status::Failed;
        outcome.exitCode = tally.firstFailure;
        outcome.error = tally.firstError;
        outcome.summary =
            std::to_string(tally.done) + " of " + std::to_string(tally.rois) +
            " ROIs done; failed: " + tally.failed +
            (tally.invalid.empty() ? "" : "; not a valid closed solid: " + tally.invalid);
    } else if (!tally.invalid.empty()) {
        outcome.status = EntryOutcome::Status::Failed;
        outcome.exitCode = kExitInvalidResult;
        outcome.error = "not a valid closed solid: " + tally.invalid;
        outcome.summary = std::to_string(tally.rois) + " ROIs done; " + outcome.error;
    } else {
        outcome.summary =
            std::to_string(tally.rois) + " ROI" + (tally.rois == 1 ? "" : "s") + " done";
    }
    return outcome;
}

// What a record says before the entry runs: the entry, its options as
// given and its input's files (or, in `inputFailure`, why they cannot be
// read). The rerun rule compares exactly these (app/BatchRecord).
nlohmann::ordered_json recordStart(const ManifestEntry& entry, const ReconstructSettings& settings,
                                   const std::string& version,
                                   std::optional<Failure>& inputFailure) {
    nlohmann::ordered_json options{{"roi", entry.roi.empty() ? nlohmann::ordered_json(nullptr)
                                                             : nlohmann::ordered_json(entry.roi)}};
    appendItems(options, reconstructSettingsJson(settings));
    nlohmann::ordered_json record{{"format", kRecordFormat}, {"id", entry.id},
                                  {"entry", entry.number},   {"input", entry.input},
                                  {"inputFiles", nullptr},   {"options", options},
                                  {"version", version}};
    try {
        record["inputFiles"] = inputFilesJson(inputFiles(entry.inputPath));
    } catch (...) {
        inputFailure = describeFailure(std::current_exception());
    }
    return record;
}

}  // namespace

const char* entryStatusName(EntryOutcome::Status status) {
    switch (status) {
        case EntryOutcome::Status::Done:
            return "done";
        case EntryOutcome::Status::Skipped:
            return "skipped";
        case EntryOutcome::Status::Failed:
            return "failed";
    }
    return "failed";
}

EntryOutcome::Status entryStatusNamed(const std::string& name) {
    if (name == "done") return EntryOutcome::Status::Done;
    if (name == "skipped") return EntryOutcome::Status::Skipped;
    return EntryOutcome::Status::Failed;
}

void writeFailedEntryRecord(const ManifestEntry& entry, const ReconstructSettings& base,
                            const std::string& outputFolder, const std::string& version,
                            const EntryFailure& failure) {
    const std::string& error = failure.error;
    const fs::path folder = fs::path(outputFolder) / entry.id;
    std::optional<Failure> inputFailure;
    nlohmann::ordered_json record =
        recordStart(entry, withGivenOptions(base, entry.options), version, inputFailure);
    record["complete"] = failure.lasting;
    record["exitCode"] = failure.exitCode;
    record["error"] = error;
    record["summary"] = "failed: " + error;
    record["seconds"] = 0;
    record["warnings"] = nlohmann::ordered_json::array();
    record["rois"] = nlohmann::ordered_json::array();
    fs::create_directories(folder);
    writeStreamAtomically((folder / kRecordFileName).string(),
                          [&](std::ostream& out) { out << jsonText(record, 2) << "\n"; });
}

EntryOutcome runBatchEntry(ocl::Runtime& runtime, const ManifestEntry& entry,
                           const ReconstructSettings& base, const std::string& outputFolder,
                           const std::string& version) {
    const Stopwatch watch;
    EntryOutcome outcome;
    try {
        const fs::path folder = fs::path(outputFolder) / entry.id;
        const fs::path recordPath = folder / kRecordFileName;
        const ReconstructSettings settings = withGivenOptions(base, entry.options);
        std::optional<Failure> entryFailure;
        nlohmann::ordered_json record = recordStart(entry, settings, version, entryFailure);

        const std::optional<std::string> previous = readRecordText(recordPath);
        if (!entryFailure) {
            const ResumeDecision decision = decideResume(
                previous ? &*previous : nullptr, record["inputFiles"], record["options"], version,
                [&](const std::string& mesh) { return isRegularFile((folder / mesh).string()); });
            if (decision.skip) {
                EntryOutcome skipped = outcomeOfRecord(*previous);
                skipped.seconds = watch.total();
                return skipped;
            }
        }
        // Removed first: killed from here on, the entry has no record, and a
        // rerun does it again.
        if (previous) fs::remove(recordPath);
        fs::create_directories(folder);

        GlobalOptions quiet;  // warnings go into the record, progress nowhere
        quiet.quiet = true;
        std::optional<ContourInput> input;
        std::vector<const Roi*> rois;
        if (!entryFailure) try {
                input.emplace(loadContours(entry.inputPath, quiet));
                rois = selectRois(input->contours, entry.roi, entry.roi.empty());
            } catch (...) {
                entryFailure = describeFailure(std::current_exception());
            }

        nlohmann::ordered_json warnings = nlohmann::ordered_json::array();
        RoiTally tally;
        if (input) {
            record["inputFormat"] = input->format;
            for (const InputWarning& w : input->warnings) warnings.push_back(w.toString());
            tally = reconstructRois(runtime, rois, *input, settings, folder);
        }
        outcome = outcomeOf(entryFailure, tally);
        outcome.seconds = watch.total();
        record["complete"] =
            entryFailure ? isLastingFailure(entryFailure->exitCode) : tally.lasting;
        record["exitCode"] = outcome.exitCode;
        record["error"] = entryFailure ? nlohmann::ordered_json(entryFailure->message)
                                       : nlohmann::ordered_json(nullptr);
        record["summary"] = outcome.summary;
        record["seconds"] = outcome.seconds;
        record["warnings"] = warnings;
        record["rois"] = std::move(tally.reports);
        // Written last: a record means every file it names is in place.
        writeStreamAtomically(recordPath.string(),
                              [&](std::ostream& out) { out << jsonText(record, 2) << "\n"; });
    } catch (...) {
        const Failure failure = describeFailure(std::current_exception());
        outcome.status = EntryOutcome::Status::Failed;
        outcome.exitCode = failure.exitCode;
        outcome.error = failure.message;
        outcome.summary = "failed: " + failure.message;
        outcome.seconds = watch.total();
    }
    return outcome;
}

}  // namespace dfrecon::app
