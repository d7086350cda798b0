// Text made UTF-8 at the readers: UTF-8 kept byte for byte, anything else
// read as Windows-1252, checked against the code charts (Unicode's
// cp1252.txt mapping) and RFC 3629's well-formedness table.
#include "io/files/TextEncoding.hpp"

#include <gtest/gtest.h>

namespace dfrecon {
namespace {

TEST(TextEncoding, AcceptsExactlyWellFormedUtf8) {
    EXPECT_TRUE(isUtf8(""));
    EXPECT_TRUE(isUtf8("plain ASCII"));
    EXPECT_TRUE(isUtf8("L\xC3\xA4sion"));              // ä
    EXPECT_TRUE(isUtf8("\xE2\x82\xAC"));               // €
    EXPECT_TRUE(isUtf8("\xF0\x9F\x98\x80"));           // U+1F600
    EXPECT_TRUE(isUtf8("\xF4\x8F\xBF\xBF"));           // U+10FFFF, the last
    EXPECT_FALSE(isUtf8("caf\xE9"));                   // Latin-1 é
    EXPECT_FALSE(isUtf8("\xC0\xAF"));                  // overlong '/'
    EXPECT_FALSE(isUtf8("\xE0\x80\xAF"));              // overlong, three bytes
    EXPECT_FALSE(isUtf8("\xED\xA0\x80"));              // a surrogate, U+D800
    EXPECT_FALSE(isUtf8("\xF4\x90\x80\x80"));          // above U+10FFFF
    EXPECT_FALSE(isUtf8("\xE2\x82"));                  // cut short
    EXPECT_FALSE(isUtf8("\x80"));                      // a lone continuation
    EXPECT_FALSE(isUtf8(std::string("\xC3\x00", 2)));  // a NUL where a continuation goes
}

TEST(TextEncoding, ReadsWhatIsNotUtf8AsWindows1252) {
    EXPECT_EQ(utf8FromLegacyText("caf\xE9"), "caf\xC3\xA9");
    EXPECT_EQ(utf8FromLegacyText("C\xF4t\xE9_D"), "C\xC3\xB4t\xC3\xA9_D");
    // 0x80-0x9F: Windows-1252's printable characters, not C1 controls.
    EXPECT_EQ(utf8FromLegacyText("\x80"), "\xE2\x82\xAC");                    // €
    EXPECT_EQ(utf8FromLegacyText("\x93x\x94"), "\xE2\x80\x9Cx\xE2\x80\x9D");  // “x”
    EXPECT_EQ(utf8FromLegacyText("\x9F"), "\xC5\xB8");                        // Ÿ
    // Its five unassigned bytes: the replacement character.
    EXPECT_EQ(utf8FromLegacyText("\x81"), "\xEF\xBF\xBD");
    EXPECT_EQ(utf8FromLegacyText("\xFF"), "\xC3\xBF");  // ÿ
    // UTF-8 and ASCII are kept as they are.
    EXPECT_EQ(utf8FromLegacyText("L\xC3\xA4sion"), "L\xC3\xA4sion");
    EXPECT_EQ(utf8FromLegacyText("GTV"), "GTV");
    EXPECT_TRUE(isUtf8(utf8FromLegacyText("\xC0\xAF\xED\xA0\x80\xFE")));
}

TEST(TextEncoding, DecidesLineByLine) {
    // One Latin-1 line must not turn its UTF-8 neighbours into mojibake.
    const std::string text = "1 L\xC3\xA4sion\n2 caf\xE9\r\n3 plain";
    EXPECT_EQ(utf8FromLegacyLines(text), "1 L\xC3\xA4sion\n2 caf\xC3\xA9\r\n3 plain");
    EXPECT_EQ(utf8FromLegacyLines("ok\n"), "ok\n");
}

}  // namespace
}  // namespace dfrecon
