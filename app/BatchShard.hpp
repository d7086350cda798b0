#pragma once
// Which entries of a batch manifest one task runs: every N-th, starting at
// its index I, so N tasks of an array job (Slurm, a Kubernetes Indexed Job)
// share the work without talking to each other and every entry runs in
// exactly one task (docs/cluster.md).
#include <cstddef>
#include <functional>
#include <optional>
#include <string>

namespace dfrecon::app {

struct Shard {
    std::size_t index = 0, count = 1;  // I and N: entries k with (k - 1) % N == I
    std::string source;                // where I/N came from, for the log

    /// True when 1-based entry `number` is this shard's. O(1).
    bool has(std::size_t number) const { return (number - 1) % count == index; }
};

/// "I/N" with 0 <= I < N <= kMaxShards. Throws std::invalid_argument
/// (usage, exit 1) otherwise. O(text).
Shard parseShard(const std::string& text);

/// The shard of this task: `shardOption` ("I/N") when given; else Slurm's
/// SLURM_ARRAY_TASK_ID, relative to SLURM_ARRAY_TASK_MIN and divided by
/// SLURM_ARRAY_TASK_STEP (both optional), out of SLURM_ARRAY_TASK_COUNT;
/// else Kubernetes' JOB_COMPLETION_INDEX out of `shards` (--shards N, which
/// it needs); else the whole manifest (0/1). `environment` looks a variable
/// up (std::getenv in the program, a map in the tests). Throws
/// std::invalid_argument naming the variable when a value is no number, I is
/// not below N, or --shards is given with no index to go with it. O(1).
Shard chooseShard(const std::string& shardOption, std::optional<std::size_t> shards,
                  const std::function<std::optional<std::string>(const std::string&)>& environment);

inline constexpr std::size_t kMaxShards = 1000000;

}  // namespace dfrecon::app
