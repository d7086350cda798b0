#pragma once
// One table of {name, value} pairs per enum serves both directions: the
// command line checks and parses names with it and reports print them from
// it, so a name is spelt once. Tables of enums that code below app/ names
// (kSpeedKindNames, kCapModeNames, kHoleConventionNames) live next to their
// enum; app/ reads them through these helpers. Every helper is O(table).
#include <array>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace dfrecon {

template <class Enum, std::size_t N>
using EnumNames = std::array<std::pair<const char*, Enum>, N>;

/// The name of `value`; "?" when the table lacks it (a table that misses a
/// value is a bug, and a report should still print).
template <class Enum, std::size_t N>
const char* nameOf(const EnumNames<Enum, N>& table, Enum value) {
    for (const auto& [name, known] : table)
        if (known == value) return name;
    return "?";
}

/// Every name in table order, e.g. for CLI::IsMember.
template <class Enum, std::size_t N>
std::vector<std::string> namesOf(const EnumNames<Enum, N>& table) {
    std::vector<std::string> names;
    for (const auto& entry : table) names.emplace_back(entry.first);
    return names;
}

/// The value named `name`; throws std::invalid_argument (exit 1) saying
/// `what` and listing the names.
template <class Enum, std::size_t N>
Enum parseEnum(const EnumNames<Enum, N>& table, const std::string& name, const std::string& what) {
    std::string names;
    for (const auto& [known, value] : table) {
        if (name == known) return value;
        names += std::string(names.empty() ? "" : ", ") + known;
    }
    throw std::invalid_argument(what + ": unknown name '" + name + "' (use " + names + ")");
}

}  // namespace dfrecon
