#pragma once
// Option checks for lengths and counts with messages a user can read
// (CLI11's own print the range's upper end, DBL_MAX, in 300 digits).
#include <cmath>
#include <string>

#include <CLI/CLI.hpp>

namespace dfrecon::app {

/// A finite number for which `accept` holds; otherwise "`rule`, not TEXT".
template <class Accept>
CLI::Validator numberCheck(Accept accept, const std::string& rule, const std::string& name) {
    return CLI::Validator(
        [accept, rule](std::string& text) -> std::string {
            double value = 0;
            if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value))
                return "'" + text + "' is not a number";
            return accept(value) ? "" : rule + ", not " + text;
        },
        name);
}

/// A finite number >= 0 ("must be at least 0").
inline const CLI::Validator kNonNegative =
    numberCheck([](double v) { return v >= 0; }, "must be at least 0", "NUMBER >= 0");

/// A finite number > 0 ("must be greater than 0").
inline const CLI::Validator kPositive =
    numberCheck([](double v) { return v > 0; }, "must be greater than 0", "NUMBER > 0");

}  // namespace dfrecon::app
