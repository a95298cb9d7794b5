#pragma once
// A campaign's random draws: each is a pure function of (campaign seed, sequence index, what is
// drawn), so a sequence is the same whichever shard renders it, in whatever order, and changing
// how one quantity is distributed leaves every other draw as it was.
#include <cstdint>
#include <string_view>

namespace ladarsim::campaign {

/// A uniform number in [0, 1) (53 random bits) for `what` (a name such as "objects[0][2].range_m")
/// of sequence `sequence` of the campaign seeded `seed`.
double campaign_uniform(std::uint64_t seed, std::uint64_t sequence, std::string_view what);

/// 63 random bits for the same key: a sequence's render seed.
std::uint64_t campaign_bits63(std::uint64_t seed, std::uint64_t sequence, std::string_view what);

}  // namespace ladarsim::campaign
