#include "option_checks.h"

#include <charconv>
#include <cmath>
#include <string>

namespace ladarsim::apps {

CLI::Validator whole_number(std::uint64_t lo, std::uint64_t hi) {
    const std::string range = "from " + std::to_string(lo) + " to " + std::to_string(hi);
    return CLI::Validator(
        [lo, hi, range](std::string& text) -> std::string {
            std::uint64_t value = 0;
            const char* end = text.data() + text.size();
            const auto [stop, error] = std::from_chars(text.data(), end, value);
            const bool digits = !text.empty() && text.front() != '-' && text.front() != '+';
            if (!digits || error != std::errc() || stop != end || value < lo || value > hi)
                return "'" + text + "' is not a whole number " + range;
            return {};
        },
        "INT " + range);
}

CLI::Validator positive_number(bool zero_allowed) {
    const std::string wanted = zero_allowed ? "of at least 0" : "above 0";
    return CLI::Validator(
        [zero_allowed, wanted](std::string& text) -> std::string {
            double value = 0.0;
            const char* end = text.data() + text.size();
            const auto [stop, error] = std::from_chars(text.data(), end, value);
            const bool ok = error == std::errc() && stop == end && std::isfinite(value) && (zero_allowed ? value >= 0.0 : value > 0.0);
            return ok ? std::string() : "'" + text + "' is not a number " + wanted;
        },
        zero_allowed ? "NUMBER >= 0" : "NUMBER > 0");
}

}  // namespace ladarsim::apps
