#include "io/RoiName.hpp"

#include <cstdio>

#include "contours/ContourSet.hpp"
#include "io/TextEncoding.hpp"

namespace dfrecon {

std::string roiNameProblem(std::string_view name) {
    if (name.empty()) return "is empty";
    if (name.size() > kMaxRoiNameBytes)
        return "is " + std::to_string(name.size()) + " bytes, over the " +
               std::to_string(kMaxRoiNameBytes) + " a name may have";
    if (!isUtf8(name)) return "is not UTF-8";
    for (const char c : name) {
        const unsigned char byte = static_cast<unsigned char>(c);
        if (byte < 0x20 || byte == 0x7F) {
            char code[16];
            std::snprintf(code, sizeof code, "U+%04X", unsigned(byte));
            return std::string("holds a control character (") + code + ")";
        }
    }
    return "";
}

}  // namespace dfrecon
