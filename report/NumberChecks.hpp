#pragma once
// Option checks for lengths and counts with messages a user can read
// (CLI11's own print the range's upper end, DBL_MAX, in 300 digits).
#include <cmath>
#include <string>

#include <CLI/CLI.hpp>

namespace dfrecon {

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

/// Any finite number. CLI11 reads "nan", "inf" and "1e999" as numbers,
/// which no length, area or count here means: the program adds this check
/// to every floating-point option (no description: --help is unchanged).
inline const CLI::Validator kFiniteNumber(
    [](std::string& text) -> std::string {
        double value = 0;
        if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value))
            return "'" + text + "' is not a finite number";
        return "";
    },
    "");

/// A finite number >= 0 ("must be at least 0").
inline const CLI::Validator kNonNegative =
    numberCheck([](double v) { return v >= 0; }, "must be at least 0", "NUMBER >= 0");

/// A finite number > 0 ("must be greater than 0").
inline const CLI::Validator kPositive =
    numberCheck([](double v) { return v > 0; }, "must be greater than 0", "NUMBER > 0");

/// A simplification bound: 0 (keep every triangle) when `zeroAllowed`, else
/// at least `minimumMm` (the floor below which the bound is under the
/// coordinates' resolution: simplify/Simplification.hpp, kMinMaxErrorMm).
inline CLI::Validator maxErrorCheck(double minimumMm, bool zeroAllowed) {
    const std::string floor = CLI::detail::to_string(minimumMm);
    return numberCheck([=](double v) { return (zeroAllowed && v == 0) || v >= minimumMm; },
                       zeroAllowed ? "must be 0 or at least " + floor + " mm"
                                   : "must be at least " + floor + " mm",
                       zeroAllowed ? "0 or NUMBER >= " + floor : "NUMBER >= " + floor);
}

}  // namespace dfrecon
