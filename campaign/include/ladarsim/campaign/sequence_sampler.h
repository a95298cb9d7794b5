#pragma once
// What one sequence of a campaign draws from its spec: a scenario document, a pure function of
// (spec, campaign seed, sequence index), and which split the sequence belongs to.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladarsim/campaign/campaign_spec.h"

namespace ladarsim::campaign {

struct SampledSequence {
    int index = 0;
    std::uint64_t seed = 0;   ///< the scenario's render seed
    /// A scenario (docs/scenario.md) with absolute paths: the sensor at [0, 0, sensor_height_m]
    /// cued to the first target (drone, bird or plane) drawn; objects numbered from 1 in the
    /// order of the spec's groups.
    nlohmann::json scenario;
    /// What was drawn, by the spec's names: sensor (its entry's preset or file, and which choice),
    /// sensor_height_m, atmosphere, background (null when none) and each object's values.
    nlohmann::json sampled;
};

SampledSequence sample_sequence(const CampaignSpec& spec, int index);

/// Each sequence's split ("train", "val", "test"), by sequence index: the shares times the
/// number of sequences, rounded by largest remainder, given to the sequences in an order drawn
/// from the campaign seed. Depends on the seed and the number of sequences only.
std::vector<std::string> sequence_splits(const CampaignSpec& spec);

}  // namespace ladarsim::campaign
