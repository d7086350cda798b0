#pragma once
// A scratch folder of the running test's own, removed when it goes out of
// scope: ctest runs tests in parallel processes, so the name holds the pid
// and the test's name.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace dfrecon::testing {

class TempDir {
  public:
    explicit TempDir(const std::string& prefix) {
        const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
        // Parameterised tests are named "Test/Parameter": one folder still.
        std::string name = test->name();
        for (char& c : name)
            if (c == '/') c = '_';
        path_ = std::filesystem::temp_directory_path() /
                ("dfrecon-" + prefix + "-" + std::to_string(::getpid()) + "-" + name);
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    std::string operator/(const std::string& name) const { return (path_ / name).string(); }
    std::string str() const { return path_.string(); }

  private:
    std::filesystem::path path_;
};

/// A scratch folder for the whole test process, made on first use (the
/// first call's prefix names it) and removed when the process exits: ctest
/// runs each test in its own process, and folders left behind pile up.
inline const std::filesystem::path& processScratch(const std::string& prefix) {
    struct Scratch {
        std::filesystem::path path;
        explicit Scratch(const std::string& prefix) {
            std::string pattern =
                (std::filesystem::temp_directory_path() / ("dfrecon-" + prefix + "-XXXXXX"))
                    .string();
            if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
            path = pattern;
        }
        ~Scratch() {
            std::error_code ignored;
            std::filesystem::remove_all(path, ignored);
        }
    };
    static const Scratch scratch(prefix);
    return scratch.path;
}

}  // namespace dfrecon::testing
