// Label tables: every accepted form parsed to the names and colours its
// lines state, errors located by line, and what dfrecon writes read back
// (by us and in the form the other tools expect).
#include "io/labels/LabelTable.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "contours/InputError.hpp"
#include "io/images/Colours.hpp"
#include "tests/TempDir.hpp"

namespace dfrecon {
namespace {

using testing::TempDir;

std::string written(const TempDir& dir, const std::string& name, const std::string& text) {
    const std::string path = dir / name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

TEST(LabelTable, ReadsItkSnapDescriptions) {
    const TempDir dir("labeltable");
    const LabelTable table =
        readLabelTable(written(dir, "snap.txt",
                               "################################################\n"
                               "# ITK-SnAP Label Description File\n"
                               "    0     0    0    0        0  0  0    \"Clear Label\"\n"
                               "    1   255    0    0        1  1  1    \"Left lung\"\n"
                               "   12     0   70  255      0.5  1  0    \"Cord\"\r\n"));
    ASSERT_EQ(table.size(), 3u);
    EXPECT_EQ(table.at(1).name, "Left lung");
    EXPECT_EQ(table.at(1).colour, (Rgb{255, 0, 0}));
    EXPECT_EQ(table.at(12).name, "Cord");
    EXPECT_EQ(table.at(12).colour, (Rgb{0, 70, 255}));
}

TEST(LabelTable, ReadsColourTablesPlainListsAndAal) {
    const TempDir dir("labeltable");
    const LabelTable lut = readLabelTable(written(dir, "FreeSurferColorLUT.lut",
                                                  "#No. Label Name: R G B A\n\n"
                                                  "0   Unknown      0   0   0   0\n"
                                                  "2   Left-Cerebral-White-Matter 245 245 245 0\n"
                                                  "1035 ctx-lh-insula 255 192 32\n"));
    EXPECT_EQ(lut.at(2).name, "Left-Cerebral-White-Matter");
    EXPECT_EQ(lut.at(2).colour, (Rgb{245, 245, 245}));
    EXPECT_EQ(lut.at(1035).colour, (Rgb{255, 192, 32}));

    const LabelTable plain =
        readLabelTable(written(dir, "AAL3v1.nii.txt", "1 Precentral_L 1\n2 Precentral_R 2\n"));
    EXPECT_EQ(plain.at(2).name, "Precentral_R");
    EXPECT_FALSE(plain.at(2).colour);

    const LabelTable aal = readLabelTable(written(
        dir, "ROI_MNI_V4.txt", "PreCG.L\tPrecentral_L\t2001\nPreCG.R\tPrecentral_R\t2002\n"));
    EXPECT_EQ(aal.at(2002).name, "Precentral_R");
}

TEST(LabelTable, LocatesWhatIsWrong) {
    const TempDir dir("labeltable");
    const auto lineOfError = [&](const std::string& text) {
        try {
            readLabelTable(written(dir, "bad.txt", text));
        } catch (const InputError& e) {
            return e.line();
        }
        return -1;
    };
    EXPECT_EQ(lineOfError("1 a 1 2 3\n2 b 1 256 3\n"), 2);           // colour past 255
    EXPECT_EQ(lineOfError("# x\n1 a\n1 b\n"), 3);                    // value listed twice
    EXPECT_EQ(lineOfError("1 2 3 4 5 6 7 \"open\n"), 1);             // unclosed quote
    EXPECT_EQ(lineOfError("5000000000 big\n"), 1);                   // past int32
    EXPECT_EQ(lineOfError("just-one-token\n"), 1);                   // no form
    EXPECT_EQ(lineOfError(std::string("1 a\n2 b\0c\n", 10)), 2);     // binary
    EXPECT_EQ(lineOfError("1 " + std::string(300, 'n') + "\n"), 1);  // name too long
    EXPECT_THROW(readLabelTable(dir / "missing.txt"), InputError);
}

TEST(LabelTable, WritesWhatItAndTheOtherToolsRead) {
    const TempDir dir("labeltable");
    const LabelTable table{{1, {"Left lung", Rgb{10, 20, 30}}}, {7, {"Cord", std::nullopt}}};
    for (const char* name : {"t.txt", "t.ctbl", "t.lut"}) {
        writeLabelTable(dir / name, table);
        const LabelTable back = readLabelTable(dir / name);
        ASSERT_EQ(back.size(), std::string(name) == "t.txt" ? 3u : 2u) << name;  // + Clear Label
        EXPECT_EQ(back.at(1).colour, (Rgb{10, 20, 30})) << name;
        EXPECT_EQ(back.at(1).name, std::string(name) == "t.txt" ? "Left lung" : "Left_lung");
        EXPECT_EQ(back.at(7).colour, categoricalColour(7)) << name;
    }
    EXPECT_THROW(writeLabelTable(dir / "t.csv", table), std::invalid_argument);
}

TEST(LabelTable, SegmentationKeysRoundTrip) {
    const LabelTable table{{1, {"Liver", Rgb{221, 130, 101}}}, {4, {"Tumour", Rgb{0, 0, 255}}}};
    const auto keys = segmentationKeys(table, {10, 20, 30});
    const LabelTable back = labelTableFromSegmentation("s.seg.nrrd", keys);
    ASSERT_EQ(back.size(), 2u);
    EXPECT_EQ(back.at(1).name, "Liver");
    EXPECT_EQ(back.at(1).colour, (Rgb{221, 130, 101}));
    EXPECT_EQ(back.at(4).colour, (Rgb{0, 0, 255}));
    EXPECT_NE(std::find(keys.begin(), keys.end(),
                        std::pair<std::string, std::string>{"Segment1_Extent", "0 9 0 19 0 29"}),
              keys.end());

    // Segments on two layers: each layer's own table; a layer the volume
    // lacks is refused.
    const auto twoLayers = segmentationKeys(table, {10, 20, 30}, {{4, 1}});
    const LabelTable first = labelTableFromSegmentation("s.seg.nrrd", twoLayers, 0, 2);
    const LabelTable second = labelTableFromSegmentation("s.seg.nrrd", twoLayers, 1, 2);
    ASSERT_EQ(first.size(), 1u);
    EXPECT_EQ(first.at(1).name, "Liver");
    ASSERT_EQ(second.size(), 1u);
    EXPECT_EQ(second.at(4).name, "Tumour");
    EXPECT_THROW(labelTableFromSegmentation("s.seg.nrrd", twoLayers), InputError);
    auto badColour = keys;
    for (auto& [key, value] : badColour)
        if (key == "Segment0_Color") value = "1 2";
    EXPECT_THROW(labelTableFromSegmentation("s.seg.nrrd", badColour), InputError);
}

TEST(LabelTable, FindsTheTableBesideAVolume) {
    const TempDir dir("labeltable");
    EXPECT_FALSE(labelTableBeside(dir / "atlas.nii.gz"));
    written(dir, "atlas-labels.txt", "1 a\n");
    EXPECT_EQ(labelTableBeside(dir / "atlas.nii.gz"), dir / "atlas-labels.txt");
    written(dir, "atlas.ctbl", "1 a 1 2 3 255\n");
    EXPECT_EQ(labelTableBeside(dir / "atlas.nii.gz"), dir / "atlas.ctbl");
    EXPECT_EQ(labelTableBeside(dir / "atlas.seg.nrrd"), dir / "atlas.ctbl");
}

TEST(LabelTable, RefusesColoursAndNamesThatAreNone) {
    const TempDir dir("labeltable-hostile");
    // A colour of 1e9 or nan was dropped silently (the line read as a plain
    // list); a control character reached the reports (exit 3).
    const std::pair<std::string, std::string> cases[] = {
        {"1 torus 1e9 0 0\n", "t.txt:1: red '1e9' is not in 0..255"},
        {"1 torus 0 nan 0 255\n", "t.txt:1: green 'nan' is not in 0..255"},
        {"1 torus 0 0 -1\n", "t.txt:1: blue '-1' is not in 0..255"},
        {"1 tor\x1bus\n", "t.txt:1: a control character (0x1B) in the name"},
        {"1 " + std::string(257, 'x') + "\n", "t.txt:1: name longer than 256 bytes"},
    };
    for (const auto& [text, message] : cases) {
        try {
            readLabelTable(written(dir, "t.txt", text));
            ADD_FAILURE() << "accepted " << text;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
        }
    }
    // Words after a name are no colour: a plain list, as before.
    EXPECT_EQ(readLabelTable(written(dir, "t.txt", "5 Left Superior Frontal\n")).at(5).name,
              "Left");
}

TEST(LabelTable, ReadsLatin1NamesAndWritesQuotesAsApostrophes) {
    const TempDir dir("labeltable-text");
    const LabelTable table =
        readLabelTable(written(dir, "t.txt", "1 C\xF4t\xE9_D\n2 L\xC3\xA4sion\n3 a\"b\n"));
    EXPECT_EQ(table.at(1).name, "C\xC3\xB4t\xC3\xA9_D");  // Windows-1252, line by line
    EXPECT_EQ(table.at(2).name, "L\xC3\xA4sion");
    // ITK-SNAP's quoted labels cannot hold a quote (found by fuzz_batch_texts).
    writeLabelTable(dir / "back.txt", table);
    EXPECT_EQ(readLabelTable(dir / "back.txt").at(3).name, "a'b");
    EXPECT_EQ(readLabelTable(dir / "back.txt").at(1).name, table.at(1).name);
}

}  // namespace
}  // namespace dfrecon
