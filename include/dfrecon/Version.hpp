#pragma once
// The library's version, "MAJOR.MINOR.PATCH" (CMake's project version).

namespace dfrecon {

/// The version these libraries were built as. O(1).
const char* version();

}  // namespace dfrecon
