// libFuzzer target for ROI expressions (`combine --expr`, docs/fuzzing.md):
// the input is one definition, checked by tests/fuzz/ExpressionOracle.hpp.
#include <cstdint>
#include <string>

#include "tests/fuzz/ExpressionOracle.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string definition(reinterpret_cast<const char*>(data), size);
    if (!dfrecon::fuzzing::expressionHolds(definition)) __builtin_trap();
    return 0;
}
