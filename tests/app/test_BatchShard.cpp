// Shards: every entry in exactly one shard; I/N from --shard, Slurm's array
// variables or a Kubernetes completion index, and clear errors otherwise.
#include <gtest/gtest.h>

#include <map>
#include <stdexcept>

#include "app/BatchShard.hpp"

using namespace dfrecon::app;

namespace {

auto environment(std::map<std::string, std::string> variables) {
    return [variables](const std::string& name) -> std::optional<std::string> {
        const auto it = variables.find(name);
        return it == variables.end() ? std::nullopt : std::optional(it->second);
    };
}

std::string problem(const std::string& shard, std::optional<std::size_t> shards,
                    std::map<std::string, std::string> variables) {
    try {
        chooseShard(shard, shards, environment(variables));
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(BatchShard, EveryEntryInExactlyOneShard) {
    for (std::size_t count : {1u, 2u, 3u, 7u, 20u}) {
        for (std::size_t entry = 1; entry <= 50; ++entry) {
            int owners = 0;
            for (std::size_t index = 0; index < count; ++index)
                owners += Shard{index, count, ""}.has(entry);
            EXPECT_EQ(owners, 1) << entry << " of " << count;
        }
    }
    // Round robin: shard 1 of 3 has entries 2, 5, 8.
    const Shard s = parseShard("1/3");
    EXPECT_TRUE(s.has(2) && s.has(5) && s.has(8));
    EXPECT_FALSE(s.has(1) || s.has(3) || s.has(4));
}

TEST(BatchShard, ChosenFromOptionSlurmOrKubernetes) {
    const auto none = environment({});
    const Shard whole = chooseShard("", std::nullopt, none);
    EXPECT_EQ(whole.index, 0u);
    EXPECT_EQ(whole.count, 1u);

    const Shard given =
        chooseShard("2/5", std::nullopt,
                    environment({{"SLURM_ARRAY_TASK_ID", "0"}, {"SLURM_ARRAY_TASK_COUNT", "3"}}));
    EXPECT_EQ(given.index, 2u);  // --shard wins over the environment
    EXPECT_EQ(given.count, 5u);

    const Shard slurm =
        chooseShard("", std::nullopt,
                    environment({{"SLURM_ARRAY_TASK_ID", "2"}, {"SLURM_ARRAY_TASK_COUNT", "3"}}));
    EXPECT_EQ(slurm.index, 2u);
    EXPECT_EQ(slurm.count, 3u);
    EXPECT_NE(slurm.source.find("SLURM_ARRAY_TASK_ID"), std::string::npos);

    // --array=1-3 and --array=10-20:5 number their tasks from MIN by STEP.
    const Shard fromOne = chooseShard("", std::nullopt,
                                      environment({{"SLURM_ARRAY_TASK_ID", "3"},
                                                   {"SLURM_ARRAY_TASK_MIN", "1"},
                                                   {"SLURM_ARRAY_TASK_COUNT", "3"}}));
    EXPECT_EQ(fromOne.index, 2u);
    const Shard stepped = chooseShard("", std::nullopt,
                                      environment({{"SLURM_ARRAY_TASK_ID", "15"},
                                                   {"SLURM_ARRAY_TASK_MIN", "10"},
                                                   {"SLURM_ARRAY_TASK_STEP", "5"},
                                                   {"SLURM_ARRAY_TASK_COUNT", "3"}}));
    EXPECT_EQ(stepped.index, 1u);

    const Shard k8s = chooseShard("", 4, environment({{"JOB_COMPLETION_INDEX", "3"}}));
    EXPECT_EQ(k8s.index, 3u);
    EXPECT_EQ(k8s.count, 4u);
}

TEST(BatchShard, ProblemsSayWhatIsWrong) {
    EXPECT_NE(problem("3/3", {}, {}).find("index 3 is not below the shard count 3"),
              std::string::npos);
    EXPECT_NE(problem("1", {}, {}).find("is not I/N"), std::string::npos);
    EXPECT_NE(problem("a/2", {}, {}).find("'a' is not a whole number"), std::string::npos);
    EXPECT_NE(problem("-1/2", {}, {}).find("not a whole number"), std::string::npos);
    EXPECT_NE(problem("0/0", {}, {}).find("no shards"), std::string::npos);
    EXPECT_NE(problem("0/99999999", {}, {}).find("not a whole number"), std::string::npos);
    EXPECT_NE(problem("", {}, {{"SLURM_ARRAY_TASK_ID", "1"}}).find("SLURM_ARRAY_TASK_COUNT"),
              std::string::npos);
    EXPECT_NE(problem("", {}, {{"SLURM_ARRAY_TASK_ID", "x"}, {"SLURM_ARRAY_TASK_COUNT", "3"}})
                  .find("SLURM_ARRAY_TASK_ID: 'x'"),
              std::string::npos);
    EXPECT_NE(problem("", {}, {{"SLURM_ARRAY_TASK_ID", "5"}, {"SLURM_ARRAY_TASK_COUNT", "3"}})
                  .find("not below"),
              std::string::npos);
    EXPECT_NE(problem("", {}, {{"JOB_COMPLETION_INDEX", "1"}}).find("give --shards N"),
              std::string::npos);
    EXPECT_NE(problem("", 3, {}).find("needs JOB_COMPLETION_INDEX"), std::string::npos);
    EXPECT_NE(problem("0/2", 2, {}).find("exclude each other"), std::string::npos);
}
