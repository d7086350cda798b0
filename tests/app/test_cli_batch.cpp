// dfrecon batch and batch-report as a user runs them: records, resuming,
// shards that give the same report as one run, a task killed midway, and
// manifests refused before anything runs.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "tests/CliRun.hpp"
#include "tests/TempDir.hpp"

namespace fs = std::filesystem;
using dfrecon::testing::slurp;
using dfrecon::testing::TempDir;

namespace {

using Run = dfrecon::testing::CliResult;

// dfrecon ARGS with `environment` ("A=1 B=2") exported to it.
Run runDfrecon(const TempDir& dir, const std::string& args, const std::string& environment = "") {
    return dfrecon::testing::runCli(dir.str(), args,
                                    environment.empty() ? "" : "export " + environment + "; ");
}

// Inputs of every kind a batch meets: synthetic shapes, an example with two
// ROIs, a broken file and a missing one; `manifest` lists them.
void makeArchive(const TempDir& dir) {
    for (const char* shape : {"sphere", "torus", "two-blobs", "y"})
        ASSERT_EQ(runDfrecon(dir, std::string("synth ") + shape + " -o " +
                                      (dir / (std::string(shape) + ".slices")))
                      .exitCode,
                  0);
    fs::copy_file(std::string(DFRECON_EXAMPLES) + "/two-rois.slices", dir / "two-rois.slices");
    std::ofstream(dir / "broken.slices") << "dfrecon-slices 1\nroi A\nslice 0\ncontour 2\n0 0\n";
    std::ofstream(dir / "manifest.csv") << "input,id,roi,cap,max-depth\n"
                                           "sphere.slices,sphere,,,\n"
                                           "torus.slices,torus,,dome,\n"
                                           "two-blobs.slices,,,,\n"
                                           "y.slices,y,,,6\n"
                                           "two-rois.slices,kidney,\"Left Kidney\",,\n"
                                           "two-rois.slices,both,,,\n"
                                           "broken.slices,broken,,,\n"
                                           "missing.slices,missing,,,\n";
}

nlohmann::json batchJson(const Run& run) {
    return nlohmann::json::parse(run.out, nullptr, false);
}

int countRecords(const std::string& folder) {
    int records = 0;
    for (const auto& entry : fs::directory_iterator(folder))
        records += fs::exists(entry.path() / "record.json");
    return records;
}

}  // namespace

TEST(CliBatch, RunsResumesAndShardsToTheSameReport) {
    const TempDir dir("batch");
    makeArchive(dir);
    const std::string manifest = dir / "manifest.csv";

    // One machine, two entries at once.
    const auto first =
        runDfrecon(dir, "batch " + manifest + " -o " + (dir / "one") + " -j 2 --json");
    EXPECT_EQ(first.exitCode, 2) << first.err;  // the broken and the missing file
    const nlohmann::json report = batchJson(first);
    ASSERT_TRUE(report.is_object()) << first.out;
    EXPECT_EQ(report["entries"], 8);
    EXPECT_EQ(report["done"], 6);
    EXPECT_EQ(report["failed"], 2);
    EXPECT_NE(first.err.find("entry broken (" + manifest + ":8): " + (dir / "broken.slices")),
              std::string::npos)
        << first.err;
    EXPECT_NE(first.err.find("failed entries: broken, missing"), std::string::npos) << first.err;
    EXPECT_EQ(countRecords(dir / "one"), 8);
    EXPECT_TRUE(fs::exists(dir / "one/3/record.json"));  // the entry's number: its default id
    EXPECT_TRUE(fs::exists(dir / "one/kidney/Left_Kidney.ply"));
    EXPECT_FALSE(fs::exists(dir / "one/kidney/Right_Kidney.ply"));

    const nlohmann::json torus = nlohmann::json::parse(slurp(dir / "one/torus/record.json"));
    EXPECT_EQ(torus["options"]["cap"], "dome");
    EXPECT_EQ(torus["complete"], true);
    EXPECT_EQ(torus["inputFiles"][0]["path"], "torus.slices");
    EXPECT_EQ(torus["inputFiles"][0]["sha256"].get<std::string>().size(), 64u);
    EXPECT_EQ(torus["rois"][0]["validSolid"], true);
    const nlohmann::json missing = nlohmann::json::parse(slurp(dir / "one/missing/record.json"));
    EXPECT_EQ(missing["exitCode"], 2);
    EXPECT_EQ(missing["complete"], true);  // bad input is a result: not retried
    EXPECT_TRUE(missing["inputFiles"].empty());

    // A rerun skips every entry, and still says which failed.
    const auto again = runDfrecon(dir, "batch " + manifest + " -o " + (dir / "one") + " --json");
    EXPECT_EQ(again.exitCode, 2);
    EXPECT_EQ(batchJson(again)["skipped"], 8) << again.out;

    // Two shards, one by --shard and one by Slurm's variables, into another folder.
    EXPECT_EQ(
        runDfrecon(dir, "batch " + manifest + " -o " + (dir / "two") + " --shard 0/2").exitCode, 2);
    const auto slurm = runDfrecon(dir, "batch " + manifest + " -o " + (dir / "two") + " --json",
                                  "SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_COUNT=2");
    EXPECT_EQ(batchJson(slurm)["entries"], 4) << slurm.out << slurm.err;
    EXPECT_EQ(batchJson(slurm)["done"], 3);  // 2, y, both; missing fails

    for (const char* folder : {"one", "two"})
        ASSERT_EQ(runDfrecon(dir, std::string("batch-report ") + (dir / folder) + " --no-seconds")
                      .exitCode,
                  0);
    EXPECT_EQ(slurp(dir / "one/batch-report.csv"), slurp(dir / "two/batch-report.csv"));
    EXPECT_EQ(slurp(dir / "one/batch-report.json"), slurp(dir / "two/batch-report.json"));
    const std::string csv = slurp(dir / "one/batch-report.csv");
    EXPECT_EQ(csv.substr(0, csv.find('\n')),
              "entry,roi,mesh,volumeCc,contourVolumeCc,validSolid,triangles,exitCode,error");
    EXPECT_NE(csv.find("\nkidney,Left Kidney,kidney/Left_Kidney.ply,"), std::string::npos) << csv;
    EXPECT_NE(csv.find("\nmissing,,,,,,,2,"), std::string::npos) << csv;

    // A changed input runs again; nothing else does.
    ASSERT_EQ(runDfrecon(dir, "synth sphere --spacing 3 -o " + (dir / "sphere.slices")).exitCode,
              0);
    const auto changed = runDfrecon(dir, "batch " + manifest + " -o " + (dir / "one") + " --json");
    EXPECT_EQ(batchJson(changed)["done"], 1) << changed.out;
    EXPECT_EQ(batchJson(changed)["skipped"], 7);
    // So does every entry when an option of the command line changes.
    const auto options = runDfrecon(
        dir, "batch " + manifest + " -o " + (dir / "one") + " --json --shard 0/4 --pixel-mm 0.5");
    EXPECT_EQ(batchJson(options)["done"], 2) << options.out;  // sphere, two-rois "kidney"
}

TEST(CliBatch, ARerunAfterAKillFinishesOnlyWhatWasMissing) {
    const TempDir dir("batch-kill");
    std::string manifest = "input,id\n";
    for (int i = 0; i < 6; ++i) {
        const std::string name = "s" + std::to_string(i) + ".slices";
        ASSERT_EQ(runDfrecon(dir, "synth torus --points 256 --spacing 0.5 --seed " +
                                      std::to_string(i + 1) + " -o " + (dir / name))
                      .exitCode,
                  0);
        manifest += name + ",e" + std::to_string(i) + "\n";
    }
    std::ofstream(dir / "m.csv") << manifest;

    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        const std::string m = dir / "m.csv", out = dir / "out";
        ::freopen("/dev/null", "w", stdout);
        ::execl(DFRECON_BINARY, DFRECON_BINARY, "-q", "batch", m.c_str(), "-o", out.c_str(), "-j",
                "1", static_cast<char*>(nullptr));
        ::_exit(127);
    }
    // Killed (SIGKILL: nothing of its own runs) as soon as its first record is there.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (!fs::exists(dir / "out/e0/record.json") && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    ::kill(child, SIGKILL);
    int status = 0;
    ::waitpid(child, &status, 0);
    const int finished = countRecords(dir / "out");
    ASSERT_GE(finished, 1);
    ASSERT_LT(finished, 6) << "every entry finished before the kill";
    // Every record there is whole.
    for (const auto& entry : fs::directory_iterator(dir / "out")) {
        if (!fs::exists(entry.path() / "record.json")) continue;
        EXPECT_FALSE(
            nlohmann::json::parse(slurp((entry.path() / "record.json").string()), nullptr, false)
                .is_discarded());
    }

    const auto rerun =
        runDfrecon(dir, "batch " + (dir / "m.csv") + " -o " + (dir / "out") + " --json");
    EXPECT_EQ(rerun.exitCode, 0) << rerun.err;
    EXPECT_EQ(batchJson(rerun)["skipped"], finished) << rerun.out;
    EXPECT_EQ(batchJson(rerun)["done"], 6 - finished);
    EXPECT_EQ(countRecords(dir / "out"), 6);
}

TEST(CliBatch, ABadManifestRunsNothing) {
    const TempDir dir("batch-bad");
    std::ofstream(dir / "m.csv") << "input,cap\na.slices,flat\nb.slices,round\n";
    const auto run = runDfrecon(dir, "batch " + (dir / "m.csv") + " -o " + (dir / "out"));
    EXPECT_EQ(run.exitCode, 2);
    EXPECT_NE(run.err.find(dir / "m.csv:3: cell 2 (cap): --cap: round not in"), std::string::npos)
        << run.err;
    EXPECT_FALSE(fs::exists(dir / "out"));

    std::ofstream(dir / "ok.csv") << "input\na.slices\n";
    const auto shard =
        runDfrecon(dir, "batch " + (dir / "ok.csv") + " -o " + (dir / "out") + " --shard 2/2");
    EXPECT_EQ(shard.exitCode, 1);
    EXPECT_NE(shard.err.find("index 2 is not below the shard count 2"), std::string::npos)
        << shard.err;
    const auto report = runDfrecon(dir, "batch-report " + dir.str());
    EXPECT_EQ(report.exitCode, 2);
    EXPECT_NE(report.err.find("no batch records"), std::string::npos) << report.err;
}
