#pragma once
// DIR/campaign.json, the index of a finished campaign:
//   {"software", "spec_file", "spec", "seed", "frames",
//    "splits": {"train": n, "val": n, "test": n},
//    "returns_by_class": {class: returns over every sequence},
//    "sequences": [{"id", "directory" (relative to DIR), "scenario", "split", "seed", "frames",
//                   "sampled", "returns_by_class"}]}
// A class is an object's ("drone", "bird", ...), "background" (the recorded map) or
// "false_alarm" (detector noise).
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladarsim/campaign/campaign_spec.h"

namespace ladarsim::campaign {

/// The index of `spec`'s campaign in `dir`, every sequence's dataset being there (their frames
/// are read for the counts of returns by class).
nlohmann::json campaign_index(const CampaignSpec& spec, const std::filesystem::path& dir);

/// Whether `dir` holds a campaign's index.
bool is_campaign(const std::filesystem::path& dir);

struct IndexedSequence {
    int id = 0;
    std::filesystem::path directory;  ///< absolute
    std::string split;
};

/// The sequences campaign.json in `dir` lists, in its order. Throws InputError naming the file
/// and field for a missing or malformed index, or a sequence directory that is not there.
std::vector<IndexedSequence> read_campaign_index(const std::filesystem::path& dir);

}  // namespace ladarsim::campaign
