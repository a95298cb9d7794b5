#pragma once
// Checks of option values that say, in the user's terms, what was given and what is allowed.
#include <cstdint>

#include <CLI/CLI.hpp>

namespace ladarsim::apps {

/// A whole number from `lo` to `hi`, in decimal digits: a sign, a fraction, a word or a value out
/// of range gives "'<value>' is not a whole number from <lo> to <hi>" (CLI11 puts the option's
/// name before it), so that "-1" never wraps around to 2^64 - 1.
CLI::Validator whole_number(std::uint64_t lo, std::uint64_t hi);

/// A finite number above 0 (`zero_allowed`: at least 0): otherwise "'<value>' is not a number
/// above 0" (or "of at least 0").
CLI::Validator positive_number(bool zero_allowed = false);

}  // namespace ladarsim::apps
