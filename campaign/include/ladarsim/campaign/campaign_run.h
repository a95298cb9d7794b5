#pragma once
// Rendering a campaign into one directory, resumably and in shards:
//   DIR/spec.json                     the spec rendered (with its overrides): later runs must match it
//   DIR/sequences/NNNNNN.json         each sequence's sampled scenario
//   DIR/sequences/NNNNNN/             its dataset, rendered by render_dataset as `ladarsim render` does
//   DIR/campaign.json                 the index (campaign_index.h), once every sequence is there
// A sequence is finished when its dataset is (render_dataset swaps it in whole); an unfinished
// one resumes from its NNNNNN.partial. Shard I of N renders the sequences i with i mod N = I.
#include <atomic>
#include <filesystem>
#include <functional>

#include "ladarsim/campaign/campaign_spec.h"

namespace ladarsim::campaign {

struct CampaignProgress {
    int sequence = 0;                ///< the sequence being rendered
    int frame = 0, frames = 0;       ///< its frames done, of
    int sequences_done = 0;          ///< of this shard's share, finished (before this run too; this one at its last frame)
    int sequences_in_share = 0;
    long long frames_rendered = 0;   ///< by this run
    long long frames_left = 0;       ///< of this shard's share
    double seconds = 0.0;            ///< since this run started
};

struct CampaignOptions {
    std::filesystem::path out_dir;
    int shard = 0, shards = 1;
    int threads = 0;  ///< 0 = all cores
    /// Read before each frame: when true the run stops after the frame it is on (the sequence
    /// then resumes from its NNNNNN.partial).
    const std::atomic<bool>* stop = nullptr;
    std::function<void(const CampaignProgress&)> progress;  ///< after each frame rendered
};

struct CampaignSummary {
    std::filesystem::path out_dir;   ///< absolute
    int rendered = 0;                ///< sequences finished by this run
    int already_done = 0;            ///< of this shard's share, finished before
    int in_share = 0;
    int campaign_done = 0;           ///< sequences of the whole campaign finished
    long long frames_rendered = 0;   ///< by this run
    double seconds = 0.0;
    bool interrupted = false;
    bool index_written = false;      ///< every sequence was there: campaign.json written
};

/// The directory of sequence `index`, relative to the campaign's: "sequences/000042".
std::string sequence_directory(int index);

/// Renders this shard's unfinished sequences of `spec` into `options.out_dir`, then writes
/// campaign.json when every sequence of the campaign is finished (by this run or any other).
/// `out_dir` may be absent, empty, or a campaign of the same spec (spec.json); another directory,
/// or a campaign of another spec, is an InputError naming "--out".
CampaignSummary run_campaign(const CampaignSpec& spec, const CampaignOptions& options);

}  // namespace ladarsim::campaign
