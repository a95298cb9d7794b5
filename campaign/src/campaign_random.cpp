#include "ladarsim/campaign/campaign_random.h"

#include <Random123/philox.h>

namespace ladarsim::campaign {

namespace {

/// FNV-1a: names the draw in the counter. Two names colliding in 64 bits would share a number.
std::uint64_t name_hash(std::string_view what) {
    std::uint64_t h = 14695981039346656037ull;
    for (const char c : what) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
    return h;
}

std::uint64_t bits64(std::uint64_t seed, std::uint64_t sequence, std::string_view what) {
    using Philox = r123::Philox4x32;
    const std::uint64_t name = name_hash(what);
    const Philox::key_type key = {{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)}};
    const Philox::ctr_type counter = {{static_cast<std::uint32_t>(sequence), static_cast<std::uint32_t>(sequence >> 32),
                                       static_cast<std::uint32_t>(name), static_cast<std::uint32_t>(name >> 32)}};
    const Philox::ctr_type bits = Philox{}(counter, key);
    return (std::uint64_t{bits[0]} << 32) | bits[1];
}

}  // namespace

double campaign_uniform(std::uint64_t seed, std::uint64_t sequence, std::string_view what) {
    return static_cast<double>(bits64(seed, sequence, what) >> 11) * 0x1.0p-53;
}

std::uint64_t campaign_bits63(std::uint64_t seed, std::uint64_t sequence, std::string_view what) {
    return bits64(seed, sequence, what) >> 1;
}

}  // namespace ladarsim::campaign
