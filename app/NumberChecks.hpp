#pragma once
// Option checks for lengths and counts with messages a user can read
// (CLI11's own print the range's upper end, DBL_MAX, in 300 digits).
#include <cmath>
#include <string>

#include <CLI/CLI.hpp>

namespace dfrecon::app {

/// A finite number >= 0 ("must be at least 0").
inline const CLI::Validator kNonNegative(
    [](std::string& text) -> std::string {
        double value = 0;
        if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value))
            return "'" + text + "' is not a number";
        return value >= 0 ? "" : "must be at least 0, not " + text;
    },
    "NUMBER >= 0");

/// A finite number > 0 ("must be greater than 0").
inline const CLI::Validator kPositive(
    [](std::string& text) -> std::string {
        double value = 0;
        if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value))
            return "'" + text + "' is not a number";
        return value > 0 ? "" : "must be greater than 0, not " + text;
    },
    "NUMBER > 0");

}  // namespace dfrecon::app
