#pragma once
// Batch entries run in worker processes of this same program, so that an
// entry whose process dies — a crash in dfrecon or a library, the kernel's
// out-of-memory killer — fails alone: its outcome and record name the
// signal, and the entries after it go on in a fresh worker. A worker is the
// same command line started again with DFRECON_BATCH_WORKER=1 in its
// environment; it reads entry positions from standard input, one per line,
// and answers each with one line of JSON on standard output.
#include <sys/types.h>
#include <cstddef>
#include <functional>
#include <string>

#include "app/BatchEntry.hpp"

namespace dfrecon::app {

/// Keeps the command line main() was given, for starting workers. Call once
/// before parsing.
void keepProgramArguments(int argc, char** argv);

/// Whether this process is a batch worker (its environment says so).
bool isBatchWorkerProcess();

/// The worker's side: until standard input ends, reads a position, calls
/// `run(position)` and writes the outcome as one JSON line, flushed. For
/// tests only: with DFRECON_BATCH_WORKER_CRASH_ENTRY=ID in the environment
/// the worker raises SIGSEGV on starting the entry with that id (`idOf`),
/// the one way to prove that a crash stays with its entry now that no
/// known input crashes.
void serveBatchEntries(const std::function<EntryOutcome(std::size_t)>& run,
                       const std::function<std::string(std::size_t)>& idOf);

/// The parent's side: one worker process, started on first use and again
/// after it died. Not thread-safe; give each thread its own.
class BatchWorker {
  public:
    BatchWorker() = default;
    BatchWorker(const BatchWorker&) = delete;
    BatchWorker& operator=(const BatchWorker&) = delete;
    ~BatchWorker();  // ends the worker: closes its input, waits for it

    struct Result {
        EntryOutcome outcome;
        /// The worker died running the entry: outcome says how; no record
        /// was written for it.
        bool died = false;
        /// A death that the same entry would meet again (a crash signal:
        /// SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT), not one from outside
        /// (SIGKILL from the OOM killer or a scheduler).
        bool lasting = false;
    };

    /// Runs the entry at `position` in the worker. Throws std::runtime_error
    /// when no worker can be started or its answer cannot be read.
    Result run(std::size_t position);

  private:
    void start();
    Result death();  // the outcome of an entry whose worker died; reaps it

    pid_t pid_ = -1;
    int toWorker_ = -1, fromWorker_ = -1;
};

}  // namespace dfrecon::app
