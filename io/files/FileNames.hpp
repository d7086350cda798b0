#pragma once
// What a file's name says about it, the way every reader and writer here
// reads extensions: without regard to letter case (".NII.GZ" is NIfTI).
#include <algorithm>
#include <cctype>
#include <string>

namespace dfrecon {

/// Whether `path` ends in `suffix`, ignoring ASCII letter case. O(|suffix|).
inline bool endsWithIgnoringCase(const std::string& path, const std::string& suffix) {
    if (path.size() < suffix.size()) return false;
    return std::equal(suffix.rbegin(), suffix.rend(), path.rbegin(), [](char a, char b) {
        return std::tolower(static_cast<unsigned char>(a)) ==
               std::tolower(static_cast<unsigned char>(b));
    });
}

}  // namespace dfrecon
