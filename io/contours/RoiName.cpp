#include "io/contours/RoiName.hpp"

#include <cstdio>

#include "contours/ContourSet.hpp"
#include "io/files/TextEncoding.hpp"

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

std::string mendedRoiName(std::string_view name) {
    if (roiNameProblem(name).empty()) return std::string(name);
    std::string mended = utf8FromLegacyText(name);
    for (char& c : mended)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) c = '_';
    if (mended.size() > kMaxRoiNameBytes) {
        std::size_t cut = kMaxRoiNameBytes;  // at a character's start
        while (cut > 0 && (static_cast<unsigned char>(mended[cut]) & 0xC0) == 0x80) --cut;
        mended.resize(cut);
    }
    return mended.empty() ? "_" : mended;
}

}  // namespace dfrecon
