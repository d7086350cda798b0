// dfrecon batch MANIFEST -o OUT: every entry of a manifest reconstructed into
// its own folder with a record, resumable, shardable over an array job
// (docs/cli.md, docs/cluster.md).
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "api/Stopwatch.hpp"
#include "app/BatchEntry.hpp"
#include "app/BatchManifest.hpp"
#include "app/BatchShard.hpp"
#include "app/BatchWorkers.hpp"
#include "app/Commands.hpp"
#include "app/OutputOptions.hpp"
#include "app/Progress.hpp"
#include "cl/WorkerRuntimes.hpp"
#include "geometry/OrderedParallel.hpp"
#include "io/files/JsonText.hpp"
#include "report/ExitCodes.hpp"
#include "report/ReconstructSettings.hpp"

namespace dfrecon::app {

namespace {

struct BatchArgs {
    std::string manifest, output, shard;
    std::size_t shards = 0;  // --shards N for JOB_COMPLETION_INDEX; 0: not given
    unsigned jobs = 0;       // entries at once; 0: defaultJobs()
    bool json = false;
    ReconstructSettings settings;  // the defaults of every entry
};

void runBatch(const BatchArgs& args, const GlobalOptions& global) {
    namespace fs = std::filesystem;
    const Stopwatch watch;
    const std::vector<ManifestEntry> entries = readManifest(args.manifest);
    const Shard shard =
        chooseShard(args.shard, args.shards > 0 ? std::optional(args.shards) : std::nullopt,
                    [](const std::string& name) -> std::optional<std::string> {
                        const char* value = std::getenv(name.c_str());
                        return value ? std::optional<std::string>(value) : std::nullopt;
                    });
    std::vector<const ManifestEntry*> mine;
    for (const ManifestEntry& entry : entries)
        if (shard.has(entry.number)) mine.push_back(&entry);
    if (isBatchWorkerProcess()) {  // started by a BatchWorker below, with this command line
        ocl::WorkerRuntimes runtime(global.device, 1);
        serveBatchEntries(
            [&](std::size_t i) {
                return runBatchEntry(runtime[0], *mine[i], args.settings, args.output,
                                     DFRECON_VERSION);
            },
            [&](std::size_t i) { return mine[i]->id; });
        return;
    }
    fs::create_directories(args.output);

    const std::size_t jobs = jobsFor(args.jobs, mine.size());
    if (!global.quiet)
        std::cerr << "dfrecon batch: shard " << shard.index << "/" << shard.count << " ("
                  << shard.source << "): " << mine.size() << " of " << entries.size()
                  << " entries, " << jobs << " at once\n";
    // Opened here only so that a device that cannot be opened fails the
    // batch before any work; the entries run in worker processes, each with
    // its own runtime (app/BatchWorkers), so that one entry's crash is that
    // entry's failure alone.
    std::unique_ptr<ocl::WorkerRuntimes> deviceCheck;
    if (!mine.empty()) deviceCheck = std::make_unique<ocl::WorkerRuntimes>(global.device, 1);
    std::vector<std::unique_ptr<BatchWorker>> workers(jobs);
    for (auto& worker : workers) worker = std::make_unique<BatchWorker>();

    std::size_t done = 0, skipped = 0, failed = 0, invalid = 0;
    int firstFailure = 0;
    std::string failedIds, invalidIds;
    nlohmann::ordered_json results = nlohmann::ordered_json::array();
    Progress overall("batch: " + std::to_string(mine.size()) + " entries", !global.quiet);
    forEachInOrder(
        mine.size(), jobs,
        [&](std::size_t i, std::size_t worker) {
            BatchWorker::Result result = workers[worker]->run(i);
            if (result.died) try {
                    // The worker wrote no record: the batch-report must
                    // still show the entry, and a rerun skip a lasting one.
                    writeFailedEntryRecord(
                        *mine[i], args.settings, args.output, DFRECON_VERSION,
                        {result.outcome.error, result.outcome.exitCode, result.lasting});
                } catch (const std::exception& e) {
                    result.outcome.error +=
                        std::string("; its record could not be written: ") + e.what();
                }
            return result.outcome;
        },
        [&](std::size_t i, EntryOutcome outcome) {
            overall.finish();
            const ManifestEntry& entry = *mine[i];
            if (outcome.status == EntryOutcome::Status::Skipped) ++skipped;
            if (outcome.status == EntryOutcome::Status::Done) ++done;
            if (outcome.exitCode == kExitInvalidResult) {
                ++invalid;
                invalidIds += (invalidIds.empty() ? "" : ", ") + entry.id;
            } else if (outcome.exitCode != 0) {
                ++failed;
                failedIds += (failedIds.empty() ? "" : ", ") + entry.id;
                if (firstFailure == 0) firstFailure = outcome.exitCode;
            }
            if (!args.json) std::cout << entry.id << ": " << outcome.summary << "\n" << std::flush;
            if (!outcome.error.empty() && outcome.status != EntryOutcome::Status::Skipped)
                std::cerr << "dfrecon: entry " << entry.id << " (" << entry.where
                          << "): " << outcome.error << "\n"
                          << std::flush;
            results.push_back({{"id", entry.id},
                               {"entry", entry.number},
                               {"status", entryStatusName(outcome.status)},
                               {"summary", outcome.summary},
                               {"exitCode", outcome.exitCode},
                               {"seconds", outcome.seconds}});
            overall.update(double(i + 1) / double(mine.size()));
        });
    overall.finish();
    if (args.json) {
        std::cout << jsonText(nlohmann::ordered_json{{"command", "batch"},
                                                     {"manifest", args.manifest},
                                                     {"output", args.output},
                                                     {"shard",
                                                      {{"index", shard.index},
                                                       {"count", shard.count},
                                                       {"source", shard.source}}},
                                                     {"manifestEntries", entries.size()},
                                                     {"entries", mine.size()},
                                                     {"done", done},
                                                     {"skipped", skipped},
                                                     {"failed", failed},
                                                     {"notValidSolid", invalid},
                                                     {"seconds", watch.total()},
                                                     {"results", results}},
                              2)
                  << "\n";
    } else {
        std::cout << "batch: " << mine.size() << " of " << entries.size() << " entries (shard "
                  << shard.index << "/" << shard.count << "): " << done << " done, " << skipped
                  << " skipped; " << failed << " failed, " << invalid
                  << " not a valid closed solid; " << watch.total() << " s\n";
    }
    if (!failedIds.empty())
        throw ItemsFailed(
            "failed entries: " + failedIds +
                (invalidIds.empty() ? "" : "; not a valid closed solid in: " + invalidIds) +
                " (the other entries were done)",
            firstFailure);
    if (!invalidIds.empty())
        throw InvalidResult("not a valid closed solid in entries: " + invalidIds);
}

}  // namespace

void addBatchCommand(CLI::App& root, const GlobalOptions& global) {
    auto args = std::make_shared<BatchArgs>();
    CLI::App* cmd = root.add_subcommand(
        "batch", "Reconstruct every ROI of every entry of a manifest, resumably, in shards");
    cmd->footer(
        "MANIFEST is a CSV file with a header row or a JSON list of objects; keys: input "
        "(required: any file reconstruct reads, relative to the manifest's folder or absolute), "
        "id (default: the entry's number; names its folder), roi (default: every ROI with "
        "contours) and any option below without its dashes (cap, max-error, ...), which "
        "overrides the command line's for that entry. Each entry writes OUT/ID/NAME.ply per ROI "
        "(--format: another mesh format) "
        "and OUT/ID/record.json (input checksums, options, version, every ROI's result or "
        "error, seconds), the record last and atomically. A rerun skips an entry whose record "
        "is complete (no device, memory or disk failure) and whose input bytes, options and "
        "program version are unchanged. Shards: --shard I/N runs entries I+1, I+1+N, ...; "
        "without it SLURM_ARRAY_TASK_ID/SLURM_ARRAY_TASK_COUNT, or JOB_COMPLETION_INDEX with "
        "--shards N, choose the shard. One failing entry or ROI never stops the others. Exit "
        "codes: 0 every entry done, 1 usage, 2 a bad manifest (nothing runs) or the first "
        "failed entry's code (2 bad input, 3 runtime), 4 no failure but a surface is not a "
        "valid closed solid. `dfrecon batch-report OUT` tabulates the records. See "
        "docs/cli.md and docs/cluster.md.");
    cmd->add_option("manifest", args->manifest, "Manifest: CSV with a header row, or JSON list")
        ->required();
    cmd->add_option("-o,--output", args->output, "Output folder: one folder per entry")->required();
    cmd->add_option("--shard", args->shard,
                    "Run only shard I of N (I from 0): entries I+1, I+1+N, I+1+2N, ... "
                    "(default: from SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT, or "
                    "JOB_COMPLETION_INDEX with --shards; else every entry)");
    cmd->add_option("--shards", args->shards,
                    "The number of shards when JOB_COMPLETION_INDEX (Kubernetes Indexed Job) "
                    "gives the index: the Job's completions")
        ->check(CLI::Range(std::size_t(1), kMaxShards));
    cmd->add_option("-j,--jobs", args->jobs,
                    "Entries run at once, each with its own OpenCL queue (default 0: one per CPU "
                    "core; never more than one per core or per entry); an entry's ROIs run one "
                    "after the other")
        ->capture_default_str()
        ->check(CLI::Range(0, 256));
    addReconstructSettingsOptions(*cmd, args->settings);
    cmd->add_flag("--json", args->json, "Print a JSON report instead of a line per entry");
    asOutput(cmd->get_option("--output"), OutputKind::Folder);
    cmd->callback([args, &global] { runBatch(*args, global); });
}

}  // namespace dfrecon::app
