#include "option_checks.h"

#include <charconv>
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

}  // namespace ladarsim::apps
