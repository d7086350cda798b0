// A failed write keeps the previous file and leaves no temporary behind.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/files/AtomicWrite.hpp"
#include "tests/TempDir.hpp"

using namespace dfrecon;
namespace fs = std::filesystem;

static std::string slurp(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(AtomicWrite, ReplacesTargetOnSuccess) {
    const fs::path dir = fs::temp_directory_path() / "dfrecon-test-atomic-ok";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path target = dir / "out.txt";
    writeStreamAtomically(target.string(), [](std::ostream& out) { out << "first"; });
    writeStreamAtomically(target.string(), [](std::ostream& out) { out << "second"; });
    EXPECT_EQ(slurp(target), "second");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(AtomicWrite, FailureKeepsOldContentAndCleansUp) {
    const fs::path dir = fs::temp_directory_path() / "dfrecon-test-atomic-fail";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path target = dir / "mesh.ply";
    writeStreamAtomically(target.string(), [](std::ostream& out) { out << "good"; });
    EXPECT_THROW(writeStreamAtomically(target.string(),
                                       [](std::ostream& out) {
                                           out << "half";
                                           throw std::runtime_error("disk on fire");
                                       }),
                 std::runtime_error);
    EXPECT_THROW(writeAtomically(target.string(),
                                 [](const std::string& tmp) {
                                     EXPECT_EQ(fs::path(tmp).extension(),
                                               ".ply");  // format detection keeps working
                                     std::ofstream(tmp) << "partial";
                                     return false;
                                 }),
                 std::runtime_error);
    EXPECT_EQ(slurp(target), "good");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

namespace {

std::size_t entries(const std::string& dir) {
    return std::size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

}  // namespace

TEST(AtomicWrite, APlantedSymlinkIsReplacedNotFollowed) {
    const dfrecon::testing::TempDir dir("atomic-link");
    std::ofstream(dir / "victim.txt") << "precious";
    fs::create_symlink(dir / "victim.txt", dir / "out.ply");
    writeStreamAtomically(dir / "out.ply", [](std::ostream& out) { out << "mesh"; });
    EXPECT_EQ(slurp(dir / "victim.txt"), "precious");
    EXPECT_FALSE(fs::is_symlink(dir / "out.ply"));
    EXPECT_EQ(slurp(dir / "out.ply"), "mesh");
    EXPECT_EQ(entries(dir.str()), 2u);
}

TEST(AtomicWrite, TheStagePathIsPrivateAndNamedLikeTheTarget) {
    const dfrecon::testing::TempDir dir("atomic-stage");
    writeAtomically(dir / "field.vdb", [&](const std::string& staged) {
        EXPECT_EQ(fs::path(staged).filename(), "field.vdb");
        const fs::path folder = fs::path(staged).parent_path();
        EXPECT_EQ(folder.parent_path(), fs::path(dir.str()));
        EXPECT_EQ(fs::status(folder).permissions() & fs::perms::all, fs::perms::owner_all);
        std::ofstream(staged) << "grid";
        return true;
    });
    EXPECT_EQ(slurp(dir / "field.vdb"), "grid");
    EXPECT_EQ(entries(dir.str()), 1u);
}

TEST(AtomicWrite, AWriterThatReplacesTheStageFileStillWorks) {
    // Some libraries unlink a path before creating it.
    const dfrecon::testing::TempDir dir("atomic-unlink");
    writeAtomically(dir / "a.png", [](const std::string& staged) {
        fs::remove(staged);
        std::ofstream(staged) << "pixels";
        return true;
    });
    EXPECT_EQ(slurp(dir / "a.png"), "pixels");
    EXPECT_EQ(entries(dir.str()), 1u);
}

TEST(AtomicWrite, AFileSizeLimitIsAFailureNotATruncatedFile) {
    // ulimit -f stands in for a full disk: the library's writes are cut
    // short where it may not notice; the write must fail and leave nothing.
    const dfrecon::testing::TempDir dir("atomic-limit");
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        std::signal(SIGXFSZ, SIG_IGN);
        const rlimit limit{4096, 4096};
        setrlimit(RLIMIT_FSIZE, &limit);
        int code = 0;
        try {
            writeAtomically(dir / "big.ply", [](const std::string& staged) {
                std::ofstream out(staged);  // errors ignored, as some libraries do
                for (int k = 0; k < 100000; ++k) out << "0123456789";
                return true;
            });
            code = 1;
        } catch (const std::runtime_error& e) {
            code = std::string(e.what()).find("cannot write") != std::string::npos ? 0 : 2;
        }
        _exit(code);
    }
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0);
    EXPECT_EQ(entries(dir.str()), 0u);
}

TEST(AtomicWrite, SigtermDuringAWriteLeavesNothing) {
    const dfrecon::testing::TempDir dir("atomic-signal");
    int ready[2];
    ASSERT_EQ(pipe(ready), 0);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        writeAtomically(dir / "slow.ply", [&](const std::string& staged) {
            std::ofstream(staged) << "half a mesh";
            const char go = 1;
            (void)!write(ready[1], &go, 1);
            pause();  // the signal arrives here
            return true;
        });
        _exit(0);
    }
    char go = 0;
    ASSERT_EQ(read(ready[0], &go, 1), 1);
    EXPECT_GT(entries(dir.str()), 0u);  // the private folder is there
    kill(child, SIGTERM);
    int status = 0;
    waitpid(child, &status, 0);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM);
    EXPECT_EQ(entries(dir.str()), 0u);
    close(ready[0]);
    close(ready[1]);
}
