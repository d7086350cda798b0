#include "app/BatchShard.hpp"

#include <stdexcept>

namespace dfrecon::app {

namespace {

// A count or index in decimal digits, at most kMaxShards; `what` names it.
std::size_t parseCount(const std::string& text, const std::string& what) {
    if (text.empty() || text.size() > 7 ||
        text.find_first_not_of("0123456789") != std::string::npos)
        throw std::invalid_argument(what + ": '" + text + "' is not a whole number");
    const std::size_t value = std::stoul(text);
    if (value > kMaxShards)
        throw std::invalid_argument(what + ": " + text + " is more than " +
                                    std::to_string(kMaxShards));
    return value;
}

Shard checked(std::size_t index, std::size_t count, const std::string& source) {
    if (count == 0) throw std::invalid_argument(source + ": no shards (N is 0)");
    if (index >= count)
        throw std::invalid_argument(source + ": index " + std::to_string(index) +
                                    " is not below the shard count " + std::to_string(count) +
                                    " (indices run from 0 to N-1)");
    return {index, count, source};
}

}  // namespace

Shard parseShard(const std::string& text) {
    const std::size_t slash = text.find('/');
    if (slash == std::string::npos)
        throw std::invalid_argument("--shard: '" + text + "' is not I/N (e.g. 0/4)");
    return checked(parseCount(text.substr(0, slash), "--shard"),
                   parseCount(text.substr(slash + 1), "--shard"), "--shard " + text);
}

Shard chooseShard(
    const std::string& shardOption, std::optional<std::size_t> shards,
    const std::function<std::optional<std::string>(const std::string&)>& environment) {
    if (!shardOption.empty()) {
        if (shards) throw std::invalid_argument("--shard and --shards exclude each other");
        return parseShard(shardOption);
    }
    if (const auto id = environment("SLURM_ARRAY_TASK_ID")) {
        const auto count = environment("SLURM_ARRAY_TASK_COUNT");
        if (!count)
            throw std::invalid_argument(
                "SLURM_ARRAY_TASK_ID is set but SLURM_ARRAY_TASK_COUNT "
                "is not");
        const std::size_t task = parseCount(*id, "SLURM_ARRAY_TASK_ID");
        const auto minText = environment("SLURM_ARRAY_TASK_MIN");
        const auto stepText = environment("SLURM_ARRAY_TASK_STEP");
        const std::size_t first = minText ? parseCount(*minText, "SLURM_ARRAY_TASK_MIN") : 0;
        const std::size_t step = stepText ? parseCount(*stepText, "SLURM_ARRAY_TASK_STEP") : 1;
        if (step == 0 || task < first || (task - first) % step != 0)
            throw std::invalid_argument(
                "SLURM_ARRAY_TASK_ID " + *id +
                " is not on the array's range (submit it as --array=0-(N-1), or give --shard)");
        const std::size_t countValue = parseCount(*count, "SLURM_ARRAY_TASK_COUNT");
        if (shards && *shards != countValue)
            throw std::invalid_argument("--shards " + std::to_string(*shards) +
                                        " differs from SLURM_ARRAY_TASK_COUNT " + *count);
        return checked((task - first) / step, countValue,
                       "SLURM_ARRAY_TASK_ID " + *id + " of SLURM_ARRAY_TASK_COUNT " + *count);
    }
    if (const auto index = environment("JOB_COMPLETION_INDEX")) {
        if (!shards)
            throw std::invalid_argument(
                "JOB_COMPLETION_INDEX is set: give --shards N, the Job's completions");
        return checked(
            parseCount(*index, "JOB_COMPLETION_INDEX"), *shards,
            "JOB_COMPLETION_INDEX " + *index + " of --shards " + std::to_string(*shards));
    }
    if (shards)
        throw std::invalid_argument("--shards " + std::to_string(*shards) +
                                    " needs JOB_COMPLETION_INDEX (or give --shard I/N)");
    return {0, 1, "the whole manifest"};
}

}  // namespace dfrecon::app
