// What an output may name (io/files/OutputTarget): special files refused always,
// inputs refused while guarded, a file the process wrote itself and read
// back (to check it) writable again.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "io/files/AtomicWrite.hpp"
#include "io/files/InputsInUse.hpp"
#include "io/files/OutputTarget.hpp"
#include "tests/TempDir.hpp"

using namespace dfrecon;
using dfrecon::testing::TempDir;

TEST(OutputTarget, SpecialFilesAreNoTargets) {
    const TempDir dir("output-target");
    EXPECT_EQ(whyNotAFileTarget(dir / "missing.ply"), "");
    EXPECT_EQ(whyNotAFileTarget("/dev/null"), "it is a character device");
    EXPECT_EQ(whyNotAFileTarget(dir.str()), "it is a folder");
    ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0600), 0);
    EXPECT_EQ(whyNotAFileTarget(dir / "fifo"), "it is a named pipe (FIFO)");
    // A link is replaced by the write, never followed: allowed.
    std::filesystem::create_symlink("/dev/null", dir / "link");
    EXPECT_EQ(whyNotAFileTarget(dir / "link"), "");
    EXPECT_THROW(writeStreamAtomically(dir / "fifo", [](std::ostream& out) { out << "x"; }),
                 std::invalid_argument);
}

TEST(OutputTarget, SameFileUnderOtherNamesAndCase) {
    const TempDir dir("output-target");
    std::ofstream(dir / "a.txt") << "a";
    std::filesystem::create_hard_link(dir / "a.txt", dir / "b.txt");
    EXPECT_TRUE(sameFile(dir / "a.txt", dir.str() + "/./a.txt"));
    EXPECT_TRUE(sameFile(dir / "a.txt", dir / "b.txt"));
    EXPECT_FALSE(sameFile(dir / "a.txt", dir / "c.txt"));
    EXPECT_TRUE(sameFile(dir / "new.txt", dir.str() + "/sub/../new.txt"));
    EXPECT_TRUE(sameFileIgnoringCase(dir / "Lung.ply", dir / "LUNG.ply"));
    EXPECT_FALSE(sameFileIgnoringCase(dir / "Lung.ply", dir / "Lung2.ply"));
}

TEST(OutputTarget, InputsAreGuardedButWhatWasWrittenMayBeRewritten) {
    const TempDir dir("output-target");
    const std::string input = dir / "input.slices", output = dir / "output.slices";
    std::ofstream(input) << "read";
    guardInputsFromOutputs(true);
    { const ReadingInput reading(input); }
    EXPECT_THROW(checkOutputTarget(input), std::invalid_argument);
    EXPECT_NO_THROW(checkOutputTarget(output));
    // Written, read back to check it, written again (combine's lattices).
    writeStreamAtomically(output, [](std::ostream& out) { out << "first"; });
    { const ReadingInput reading(output); }
    EXPECT_NO_THROW(writeStreamAtomically(output, [](std::ostream& out) { out << "second"; }));
    guardInputsFromOutputs(false);
    EXPECT_NO_THROW(checkOutputTarget(input));  // a library's process: not guarded
}
