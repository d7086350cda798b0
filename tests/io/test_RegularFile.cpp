// The one gate before any reader: only regular files within their limit
// are opened; pipes, devices and folders are named for what they are.
#include "io/files/RegularFile.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "contours/InputError.hpp"
#include "tests/TempDir.hpp"

namespace dfrecon {
namespace {

std::string refusal(const std::string& path, std::uint64_t maxBytes) {
    try {
        checkRegularFile(path, maxBytes, "a test file");
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), path);
        return e.problem();
    }
    return "";
}

TEST(RegularFile, NamesWhatIsNotARegularFile) {
    const testing::TempDir dir("regularfile");
    const std::string fifo = dir / "pipe";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_EQ(refusal(fifo, 100), "a named pipe, not a regular file");  // and did not block
    EXPECT_EQ(refusal(dir.str(), 100), "a folder, not a regular file");
    const std::string zero = dir / "zero.json";
    std::filesystem::create_symlink("/dev/zero", zero);
    EXPECT_EQ(refusal(zero, 100), "a character device, not a regular file");
    EXPECT_EQ(refusal(dir / "missing", 100), "no such file");
    EXPECT_FALSE(isRegularFile(fifo));
    EXPECT_FALSE(isRegularFile(zero));
}

TEST(RegularFile, RefusesASparseGiantBeforeReadingIt) {
    const testing::TempDir dir("regularfile-size");
    const std::string giant = dir / "giant.slices";
    std::ofstream(giant).close();
    std::filesystem::resize_file(giant, std::uint64_t(100) << 30);  // sparse: no disk
    EXPECT_EQ(refusal(giant, std::uint64_t(1) << 30),
              "larger than 1024 MiB, the limit of a test file");
    EXPECT_THROW(readRegularFile(giant, std::uint64_t(1) << 30, "a test file"), InputError);
}

TEST(RegularFile, ReadsAWholeFileThroughALink) {
    const testing::TempDir dir("regularfile-read");
    const std::string file = dir / "a.txt";
    std::ofstream(file, std::ios::binary) << "hello\n";
    std::filesystem::create_symlink(file, dir / "link.txt");
    EXPECT_EQ(checkRegularFile(dir / "link.txt", 6, "a test file"), 6u);
    EXPECT_EQ(readRegularFile(dir / "link.txt", 6, "a test file"), "hello\n");
    EXPECT_EQ(refusal(file, 5), "larger than 5 bytes, the limit of a test file");
}

}  // namespace
}  // namespace dfrecon
