#include "io/files/Base64.hpp"

#include <cstdint>

namespace dfrecon {

std::string base64(const void* data, std::size_t size) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const auto* bytes = static_cast<const unsigned char*>(data);
    std::string text;
    text.reserve((size + 2) / 3 * 4);
    for (std::size_t k = 0; k < size; k += 3) {
        const std::uint32_t a = bytes[k], b = k + 1 < size ? bytes[k + 1] : 0,
                            c = k + 2 < size ? bytes[k + 2] : 0;
        const std::uint32_t triple = (a << 16) | (b << 8) | c;
        text += table[(triple >> 18) & 63];
        text += table[(triple >> 12) & 63];
        text += k + 1 < size ? table[(triple >> 6) & 63] : '=';
        text += k + 2 < size ? table[triple & 63] : '=';
    }
    return text;
}

void writeBase64(std::ostream& out, const void* bytes, std::size_t size) {
    out << base64(bytes, size);
}

}  // namespace dfrecon
