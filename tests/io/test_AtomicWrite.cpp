// A failed write keeps the previous file and leaves no temporary behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/AtomicWrite.hpp"

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
