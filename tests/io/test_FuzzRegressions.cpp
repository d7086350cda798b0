// Inputs the fuzzer found (tests/data/fuzz/): each must parse or fail with an
// InputError, never crash, hang or throw anything else.
#include <gtest/gtest.h>

#include <filesystem>

#include "io/SlicesFile.hpp"

using namespace dfrecon;
namespace fs = std::filesystem;

TEST(FuzzRegressions, EveryKeptInputIsHandled) {
    const fs::path dir = fs::path(DFRECON_TEST_DATA) / "fuzz";
    int files = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (!entry.is_regular_file()) continue;
        ++files;
        try {
            readSlicesFile(entry.path().string());
        } catch (const InputError&) {
            // A clear error is the expected outcome for most of these.
        }
    }
    EXPECT_GT(files, 0);
}
