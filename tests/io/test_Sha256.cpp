// SHA-256 against the FIPS 180-4 examples and the digests of the input files
// a batch record keeps (io/contours/InputDigest).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "contours/InputError.hpp"
#include "io/contours/InputDigest.hpp"
#include "io/files/Sha256.hpp"
#include "tests/TempDir.hpp"

using namespace dfrecon;
using dfrecon::testing::TempDir;

TEST(Sha256, MatchesTheStandardsExamples) {
    // FIPS 180-4 / NIST CSRC examples: empty, one block, two blocks, a million 'a'.
    EXPECT_EQ(sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    EXPECT_EQ(sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    EXPECT_EQ(sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
              "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
    EXPECT_EQ(sha256Hex(std::string(1000000, 'a')),
              "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, PiecesGiveTheDigestOfTheWhole) {
    std::string bytes;
    for (int i = 0; i < 1000; ++i) bytes += char(i * 7);
    // Pieces that straddle the 64-byte blocks and the 56-byte padding limit.
    for (std::size_t piece : {1u, 55u, 56u, 63u, 64u, 65u, 999u}) {
        Sha256 sha;
        for (std::size_t at = 0; at < bytes.size(); at += piece)
            sha.add(bytes.data() + at, std::min(piece, bytes.size() - at));
        EXPECT_EQ(sha.hex(), sha256Hex(bytes)) << piece;
    }
}

TEST(InputDigest, AFileAFolderAndAHeaderWithItsData) {
    const TempDir dir("sha");
    std::ofstream(dir / "a.slices") << "abc";
    std::filesystem::create_directories(dir / "series/sub");
    std::ofstream(dir / "series/sub/2.dcm") << "two";
    std::ofstream(dir / "series/1.dcm") << "";
    std::filesystem::create_directories(dir / "vol");
    std::ofstream(dir / "vol/v.nhdr") << "NRRD0004";
    std::ofstream(dir / "vol/v.raw") << "abc";

    const std::vector<InputFile> file = inputFiles(dir / "a.slices");
    ASSERT_EQ(file.size(), 1u);
    EXPECT_EQ(file[0].path, "a.slices");
    EXPECT_EQ(file[0].bytes, 3u);
    EXPECT_EQ(file[0].sha256, sha256Hex("abc"));

    const std::vector<InputFile> folder = inputFiles(dir / "series");
    ASSERT_EQ(folder.size(), 2u);
    EXPECT_EQ(folder[0].path, "1.dcm");
    EXPECT_EQ(folder[1].path, "sub/2.dcm");
    EXPECT_EQ(folder[1].sha256, sha256Hex("two"));

    const std::vector<InputFile> header = inputFiles(dir / "vol/v.nhdr");
    ASSERT_EQ(header.size(), 2u);
    EXPECT_EQ(header[0].path, "v.nhdr");
    EXPECT_EQ(header[1].path, "v.raw");

    EXPECT_TRUE(inputFiles(dir / "missing.slices").empty());

    // One changed byte changes the digest.
    std::ofstream(dir / "a.slices") << "abd";
    EXPECT_NE(inputFiles(dir / "a.slices")[0].sha256, file[0].sha256);
}
