// The one JSON reader: what nlohmann::json accepts silently or crashes on
// is refused with the file, line or place named, and reports never throw.
#include "io/files/JsonText.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>

#include "contours/InputError.hpp"
#include "tests/TempDir.hpp"

namespace dfrecon {
namespace {

std::string problemOf(const std::string& text, int maxDepth = 16, int* line = nullptr) {
    JsonLimits limits;
    limits.maxDepth = maxDepth;
    try {
        parseJsonText(text, "m.json", limits);
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "m.json");
        if (line) *line = e.line();
        return e.problem();
    }
    return "";
}

TEST(JsonText, ParsesWhatIsValid) {
    const nlohmann::json value =
        parseJsonText(R"([{"input": "a.slices", "n": [1, 2]}])", "m.json", JsonLimits{});
    EXPECT_EQ(value[0]["input"], "a.slices");
    EXPECT_EQ(value[0]["n"][1], 2);
}

TEST(JsonText, RefusesARepeatedKeyNamingWhere) {
    EXPECT_EQ(problemOf(R"([{"input": "a"}, {"input": "a", "id": "x", "input": "b"}])"),
              "the key 'input' a second time in one object, at /1/input (each key at most once)");
    // The same key in different objects is no repeat.
    EXPECT_EQ(problemOf(R"([{"input": "a"}, {"input": "b", "x": {"input": 1}}])"), "");
}

TEST(JsonText, RefusesNestingDeeperThanItsLimitBeforeBuildingIt) {
    // 100 000 levels crashed batch-report (its dump recursed).
    const std::string deep = std::string(100000, '[') + std::string(100000, ']');
    EXPECT_EQ(problemOf(deep),
              "lists or objects nested more than 16 deep, at /0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0");
    EXPECT_EQ(problemOf(R"([{"a": {"b": 1}}])", 2),
              "lists or objects nested more than 2 deep, at /0/a");
    EXPECT_EQ(problemOf(R"([{"a": 1}])", 2), "");
}

TEST(JsonText, NamesTheLineOfASyntaxError) {
    int line = 0;
    const std::string problem = problemOf("[\n{\"a\": 1},\n{\"a\": }\n]", 16, &line);
    EXPECT_EQ(line, 3);
    EXPECT_NE(problem.find("not valid JSON"), std::string::npos) << problem;
}

TEST(JsonText, ReadsLatin1LinesAsWindows1252) {
    const nlohmann::json value = parseJsonText(
        "[{\"id\": \"caf\xE9\"},\n{\"id\": \"L\xC3\xA4sion\"}]", "m.json", JsonLimits{});
    EXPECT_EQ(value[0]["id"], "caf\xC3\xA9");
    EXPECT_EQ(value[1]["id"], "L\xC3\xA4sion");
}

TEST(JsonText, WritesNamesThatAreNotUtf8WithoutThrowing) {
    const nlohmann::ordered_json report{{"file", "caf\xE9.slices"}};
    EXPECT_EQ(jsonText(report), "{\"file\":\"caf\xEF\xBF\xBD.slices\"}");
    EXPECT_THROW((void)report.dump(), nlohmann::json::type_error);  // what it replaces
}

TEST(JsonText, ReadsOnlyRegularFilesWithinTheLimit) {
    const testing::TempDir dir("jsontext");
    const std::string fifo = dir / "record.json";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    try {
        readJsonFile(fifo, JsonLimits{}, "a batch record");
        FAIL() << "a named pipe was opened";
    } catch (const InputError& e) {
        EXPECT_EQ(e.problem(), "a named pipe, not a regular file");
    }
    const std::string big = dir / "big.json";
    std::ofstream(big) << "[" << std::string(2000, ' ') << "]";
    JsonLimits limits;
    limits.maxBytes = 1000;
    try {
        readJsonFile(big, limits, "a batch record");
        FAIL() << "over the limit";
    } catch (const InputError& e) {
        EXPECT_EQ(e.problem(), "larger than 1000 bytes, the limit of a batch record");
    }
}

}  // namespace
}  // namespace dfrecon
