// CLI11 validators for what CLI11's own checks let through: an empty value given explicitly
// (`--size ''` would otherwise mean "the default"), NaN (CLI::Range and CLI::PositiveNumber compare
// with < and >, which NaN passes), and integers beyond their type (CLI11 clamps 2^63 to
// INT64_MAX). A failed check is a CLI11 ValidationError: "--ipd: ...", exit status 2.
#pragma once
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

#include "core/util/UserFile.h"

namespace fovea::app {

inline std::string shortNumber(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

// Rejects an explicitly empty value.
inline CLI::Validator nonEmptyValue() {
    return CLI::Validator(
        [](std::string& value) {
            return value.empty()
                       ? std::string("must not be empty (omit the option for the default)")
                       : std::string();
        },
        "NON-EMPTY");
}

// A path the operating system can look up (pathProblem: names of at most 255 bytes, no loop of
// symbolic links), so a bad one is exit 2 naming the flag.
inline CLI::Validator userPath() {
    return CLI::Validator([](std::string& value) { return pathProblem(value); }, "PATH");
}

// A finite number in [min, max] (NaN and infinities rejected).
inline CLI::Validator finiteRange(double min, double max) {
    return CLI::Validator(
        [min, max](std::string& value) {
            char* end = nullptr;
            const double v = std::strtod(value.c_str(), &end);
            if (value.empty() || *end != '\0' || !std::isfinite(v) || v < min || v > max)
                return "expected a finite number in [" + shortNumber(min) + ", " +
                       shortNumber(max) + "], got '" + value + "'";
            return std::string();
        },
        "FINITE");
}

// A finite number > 0.
inline CLI::Validator finitePositive() {
    return CLI::Validator(
        [](std::string& value) {
            char* end = nullptr;
            const double v = std::strtod(value.c_str(), &end);
            if (value.empty() || *end != '\0' || !std::isfinite(v) || !(v > 0.0))
                return "expected a finite number > 0, got '" + value + "'";
            return std::string();
        },
        "POSITIVE");
}

// A decimal integer in [0, INT64_MAX], checked on the text (before CLI11 converts and clamps).
inline CLI::Validator nonNegativeInt64() {
    return CLI::Validator(
        [](std::string& value) {
            const bool digits = !value.empty() && value.size() <= 19 &&
                                value.find_first_not_of("0123456789") == std::string::npos;
            errno = 0;
            const unsigned long long v = digits ? std::strtoull(value.c_str(), nullptr, 10) : 0;
            if (!digits || errno == ERANGE || v > uint64_t(std::numeric_limits<int64_t>::max()))
                return "expected an integer in [0, 9223372036854775807], got '" + value + "'";
            return std::string();
        },
        "INT64");
}

}  // namespace fovea::app
