// Batch manifests: CSV as RFC 4180 writes it and JSON lists read alike;
// every problem refused with the file, the line and the column or key.
#include <gtest/gtest.h>

#include <fstream>

#include "app/BatchManifest.hpp"
#include "contours/InputError.hpp"
#include "tests/TempDir.hpp"

using namespace dfrecon;
using namespace dfrecon::app;

namespace {

std::vector<ManifestEntry> parse(const std::string& text) {
    return parseManifest(text, "m.csv", "/data");
}

// The message of the InputError that parsing `text` throws, or "".
std::string problem(const std::string& text) {
    try {
        parse(text);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(BatchManifest, CsvWithQuotesDefaultsAndOptions) {
    const auto entries = parse(
        "\xEF\xBB\xBFinput,id,roi,cap,max-error\r\n"
        "a.slices,,,,\r\n"
        "\r\n"
        " \"b, with comma.dcm\" , p-2 ,\"GTV \"\"left\"\"\",dome,0.5\n"
        "/abs/c.nrrd,p3,\"multi\nline\",,\n");
    ASSERT_EQ(entries.size(), 3u);
    EXPECT_EQ(entries[0].id, "1");  // the entry's number
    EXPECT_EQ(entries[0].inputPath, "/data/a.slices");
    EXPECT_EQ(entries[0].roi, "");
    EXPECT_TRUE(entries[0].options.empty());  // empty cells: the defaults
    EXPECT_EQ(entries[0].where, "m.csv:2");
    EXPECT_EQ(entries[1].input, "b, with comma.dcm");
    EXPECT_EQ(entries[1].id, "p-2");
    EXPECT_EQ(entries[1].roi, "GTV \"left\"");
    ASSERT_EQ(entries[1].options.size(), 2u);
    EXPECT_EQ(entries[1].options[0].name, "cap");
    EXPECT_EQ(entries[1].options[0].value, "dome");
    EXPECT_EQ(entries[1].options[1].name, "max-error");
    EXPECT_EQ(entries[1].line, 4);
    EXPECT_EQ(entries[2].inputPath, "/abs/c.nrrd");
    EXPECT_EQ(entries[2].roi, "multi\nline");
    EXPECT_EQ(entries[2].number, 3u);
}

TEST(BatchManifest, JsonListReadsLikeCsv) {
    const auto entries = parseManifest(
        "  [{\"input\": \"a.slices\"},\n"
        "   {\"input\": \"b.dcm\", \"id\": \"p2\", \"roi\": \"GTV\", \"cap\": \"none\",\n"
        "    \"max-depth\": 6, \"max-error\": 0.25, \"ascii\": true, \"pixel-mm\": null}]",
        "m.json", "rel");
    ASSERT_EQ(entries.size(), 2u);
    EXPECT_EQ(entries[0].id, "1");
    EXPECT_EQ(entries[0].inputPath, "rel/a.slices");
    EXPECT_EQ(entries[0].where, "m.json: entry 1");
    EXPECT_EQ(entries[1].roi, "GTV");
    ASSERT_EQ(entries[1].options.size(), 4u);  // null: the default
    const ReconstructSettings s = withGivenOptions({}, entries[1].options);
    EXPECT_EQ(s.options.cap, CapMode::None);
    EXPECT_EQ(s.options.maxDepth, 6);
    EXPECT_EQ(s.maxErrorMm, 0.25);
    EXPECT_TRUE(s.ascii);
}

TEST(BatchManifest, ProblemsNameTheFileLineAndColumnOrKey) {
    const struct {
        std::string text, message;
    } cases[] = {
        {"", "m.csv: no header row"},
        {"id,roi\nx,y\n", "m.csv:1: no 'input' column"},
        {"input,colour\na,b\n", "m.csv:1: column 7: unknown key 'colour'"},
        {"input,input\na,b\n", "m.csv:1: column 7: the key 'input' a second time"},
        {"input,id\na\n", "m.csv:2: column 1: 1 cells where the header has 2"},
        {"input,id\na,b,c\n", "m.csv:2: column 5: 3 cells where the header has 2"},
        {"input,id\n\"a,b\n", "m.csv:2: column 1: a quoted cell that is never closed"},
        {"input,id\n\"a\"x,b\n", "m.csv:2: column 4: text after a closing quote"},
        {"input,id\na\"b,c\n", "m.csv:2: column 2: a quote inside an unquoted cell"},
        {"input,id\n,p1\n", "m.csv:2: no input"},
        {"input,id\na,up/down\n", "m.csv:2: cell 2 (id): an id with a character other than"},
        {"input,id\na,../up\n", "m.csv:2: cell 2 (id): an id starting with '.'"},
        {"input,id\na,.hidden\n", "m.csv:2: cell 2 (id): an id starting with '.'"},
        {"input,id\na,Batch-Report.csv\n", "the name of a report batch-report writes"},
        {"input,id\na,p1\nb,P1\n", "m.csv:3: the id 'P1' is already line 2's ('p1')"},
        {"input,id\na,\nb,1\n", "m.csv:3: the id '1' is already line 2's"},  // a default id
        {"input,cap\na,round\n", "m.csv:2: cell 2 (cap): --cap: round not in"},
        {"input,max-depth\na,99\n", "m.csv:2: cell 2 (max-depth): --max-depth"},
        {"input,max-error\na,-1\n", "must be 0 or at least 1e-06 mm, not -1"},
        {"input,ascii\na,maybe\n", "m.csv:2: cell 2 (ascii)"},
        {std::string("input\na\0b\n", 10), "m.csv:2: column 2: a NUL byte"},
        {"input\n\"" + std::string(9000, 'x') + "\"\n", "m.csv:2: column 1: a value longer"},
        {"[1]", "m.csv: entry 1: not an object"},
        {"[{\"input\": \"a\", \"colour\": 1}]", "m.csv: entry 1, key 'colour': unknown key"},
        {"[{\"input\": [\"a\"]}]", "lists or objects nested more than 2 deep, at /0/input"},
        {"[{\"id\": \"x\"}]", "m.csv: entry 1: no input"},
        {"[{\"input\": \"a\"},\n {\"input\": }]", "m.csv:2: not valid JSON"},
        {"[{\"input\": \"a\", \"cap\": \"round\"}]", "m.csv: entry 1, key 'cap': --cap"},
        {"[" + std::string(100, '[') + "]", "lists or objects nested more than 2 deep, at /0/0"},
        {"[]", "m.csv: no entries"},
        {"input\n", "m.csv: no entries"},
    };
    for (const auto& c : cases) {
        const std::string message = problem(c.text);
        EXPECT_NE(message.find(c.message), std::string::npos)
            << "manifest: " << c.text.substr(0, 60) << "\nmessage: " << message;
    }
}

TEST(BatchManifest, ReadsAFileAndResolvesAgainstItsFolder) {
    const dfrecon::testing::TempDir dir("manifest");
    std::ofstream(dir / "m.csv") << "input\nx.slices\n";
    const auto entries = readManifest(dir / "m.csv");
    ASSERT_EQ(entries.size(), 1u);
    EXPECT_EQ(entries[0].inputPath, dir / "x.slices");
    EXPECT_EQ(entries[0].where, dir / "m.csv:2");
    EXPECT_THROW(readManifest(dir / "missing.csv"), InputError);
}
