// The resume rule: a record is trusted only when it is complete and made
// from the same input bytes, options and program version, with its meshes
// still there.
#include <gtest/gtest.h>

#include "app/BatchRecord.hpp"
#include "contours/InputError.hpp"

using namespace dfrecon;
using namespace dfrecon::app;

namespace {

const nlohmann::ordered_json kFiles = inputFilesJson({{"a.slices", 3, std::string(64, 'a')}});
const nlohmann::ordered_json kOptions{{"roi", nullptr}, {"cap", "flat"}, {"max-error", 0.5}};

nlohmann::ordered_json record() {
    return {{"format", kRecordFormat},
            {"id", "p1"},
            {"entry", 1},
            {"inputFiles", kFiles},
            {"options", kOptions},
            {"version", "1.0"},
            {"complete", true},
            {"exitCode", 0},
            {"rois", {{{"roi", "A"}, {"mesh", "A.ply"}}, {{"roi", "B"}, {"mesh", nullptr}}}}};
}

ResumeDecision decide(const nlohmann::ordered_json& r, const nlohmann::ordered_json& files = kFiles,
                      const nlohmann::ordered_json& options = kOptions,
                      const std::string& version = "1.0", bool meshesThere = true) {
    const std::string text = r.dump();
    return decideResume(&text, files, options, version,
                        [&](const std::string&) { return meshesThere; });
}

}  // namespace

TEST(BatchRecord, SkipsOnlyWhatIsCompleteAndUnchanged) {
    EXPECT_TRUE(decide(record()).skip);
    // Key order and number spelling do not matter.
    nlohmann::ordered_json reordered{{"max-error", 0.50}, {"cap", "flat"}, {"roi", nullptr}};
    EXPECT_TRUE(decide(record(), kFiles, reordered).skip);

    EXPECT_FALSE(decideResume(nullptr, kFiles, kOptions, "1.0", {}).skip);
    nlohmann::ordered_json incomplete = record();
    incomplete["complete"] = false;
    EXPECT_NE(decide(incomplete).reason.find("incomplete"), std::string::npos);
    EXPECT_NE(decide(record(), kFiles, kOptions, "1.1").reason.find("version"), std::string::npos);
    nlohmann::ordered_json otherOptions = kOptions;
    otherOptions["cap"] = "dome";
    EXPECT_NE(decide(record(), kFiles, otherOptions).reason.find("options"), std::string::npos);
    const nlohmann::ordered_json otherFiles =
        inputFilesJson({{"a.slices", 3, std::string(64, 'b')}});
    EXPECT_NE(decide(record(), otherFiles).reason.find("input changed"), std::string::npos);
    EXPECT_NE(decide(record(), inputFilesJson({})).reason.find("input changed"), std::string::npos);
    EXPECT_NE(decide(record(), kFiles, kOptions, "1.0", false).reason.find("A.ply is missing"),
              std::string::npos);
}

TEST(BatchRecord, UnreadableRecordsRunAgain) {
    for (const std::string& text :
         {std::string(""), std::string("{"), std::string("[]"), std::string("{\"format\": 3}"),
          std::string("{\"format\": \"other 1\"}")}) {
        const ResumeDecision d = decideResume(&text, kFiles, kOptions, "1.0", {});
        EXPECT_FALSE(d.skip) << text;
        EXPECT_NE(d.reason.find("unreadable"), std::string::npos) << text;
    }
    nlohmann::ordered_json odd = record();
    odd["complete"] = "yes";  // a value of the wrong type
    EXPECT_FALSE(decide(odd).skip);
}

TEST(BatchRecord, OnlyRuntimeFailuresLeaveAnEntryIncomplete) {
    EXPECT_TRUE(isLastingFailure(1));
    EXPECT_TRUE(isLastingFailure(2));
    EXPECT_FALSE(isLastingFailure(3));
    EXPECT_TRUE(isLastingFailure(4));
}

TEST(BatchRecord, ParsingRefusesWhatIsNoRecordAsBadInput) {
    // Found by fuzz_batch_texts: a format that is no string escaped as the
    // JSON library's type error, not as bad input naming the record.
    for (const std::string& text :
         {std::string("{\"format\": 1}"), std::string("{\"format\": null, \"id\": \"a\"}"),
          std::string("{\"format\": \"dfrecon-batch-record 1\", \"id\": 3, \"entry\": 1}")}) {
        try {
            parseRecord(text, "r.json");
            ADD_FAILURE() << "accepted " << text;
        } catch (const InputError& e) {
            EXPECT_EQ(e.file(), "r.json");
            EXPECT_NE(e.problem().find("not a batch record"), std::string::npos) << e.problem();
        }
    }
    // A mesh outside the entry's folder: not trusted.
    for (const char* mesh : {"../x.ply", "/etc/passwd", "a/b.ply", "..", ""}) {
        nlohmann::ordered_json r = record();
        r["rois"][0]["mesh"] = mesh;
        EXPECT_THROW(parseRecord(r.dump(), "r.json"), InputError) << mesh;
        EXPECT_FALSE(decide(r).skip) << mesh;
    }
    EXPECT_TRUE(isPlainFileName("A.ply"));
    EXPECT_FALSE(isPlainFileName(std::string("A\0.ply", 6)));
}
