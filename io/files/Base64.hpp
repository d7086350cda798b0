#pragma once
// Base64 (RFC 4648, with padding): how binary arrays travel inside text
// files (VTK XML PolyData, HTML reports).
#include <cstddef>
#include <ostream>
#include <string>

namespace dfrecon {

/// `size` bytes at `bytes` as base64 text. O(size).
std::string base64(const void* bytes, std::size_t size);

/// Writes base64(bytes, size) to `out`. O(size).
void writeBase64(std::ostream& out, const void* bytes, std::size_t size);

}  // namespace dfrecon
