#include "ladarsim/campaign/campaign_run.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "ladarsim/campaign/campaign_index.h"
#include "ladarsim/campaign/sequence_sampler.h"
#include "ladarsim/core/input_error.h"
#include "ladarsim/dataset/dataset_directory.h"
#include "ladarsim/core/json_file.h"
#include "ladarsim/dataset/dataset_directory.h"
#include "ladarsim/sensor_model/render/render_dataset.h"
#include "ladarsim/sensor_model/render/scenario.h"

namespace ladarsim::campaign {

namespace {

namespace fs = std::filesystem;

/// What a run must match to continue a campaign in a directory.
nlohmann::json spec_record(const CampaignSpec& spec) {
    return {{"spec_file", fs::absolute(spec.file).lexically_normal().string()}, {"spec", spec.source}};
}

/// write_json for a file that the shards of an array job, started or finishing together, may
/// all write with the same bytes: each writes under a name of its own and renames it into place
/// (write_json's own temporary, `<path>.tmp`, would be shared).
void write_shared_json(const fs::path& path, const nlohmann::json& value) {
    char host[256] = "";
    ::gethostname(host, sizeof host - 1);
    const fs::path mine = path.string() + "." + host + "." + std::to_string(::getpid());
    write_json(mine, value);
    fs::rename(mine, path);
}

/// The entries a campaign writes at the top of its directory (the card's by scripts/plot_campaign.py).
const std::vector<std::string>& campaign_entries() {
    static const std::vector<std::string> entries{"campaign.json", "card-balance.png", "card-targets.png", "card-visibility.png",
                                                  "card.md",       "sequences",        "spec.json"};
    return entries;
}

/// Whether `dir` holds nothing but what another run starting this campaign at the same moment
/// writes first: its owned list, sequences/ (empty) and its record, those two under temporary names.
bool only_a_campaign_starting(const fs::path& dir) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir)) {
        const std::string entry = e.path().filename().string();
        const bool starting = (entry == "sequences" && fs::is_empty(e.path(), ec)) || entry.rfind("spec.json.", 0) == 0 ||
                              entry.rfind(kOwnedList, 0) == 0;
        if (!starting) return false;
    }
    return true;
}

/// Whether `record_file`, which ladarsim's owned list does not name, is this run's record all the
/// same: a campaign begun before campaigns had the list.
bool unlisted_record_matches(const fs::path& record_file, const nlohmann::json& record) {
    try {
        return read_json(record_file) == record;
    } catch (const InputError&) {
        return false;  // not even JSON: the user's
    }
}

/// The campaign directory, made ready: absent or empty (created), or a campaign of this spec
/// (its owned list names spec.json, or, from before the list, its spec.json is this run's record).
/// Its entries are listed as ladarsim's, all at once, before any is written.
fs::path prepared_campaign_dir(const CampaignSpec& spec, const fs::path& requested) {
    fs::path out = fs::absolute(requested).lexically_normal();
    if (!out.has_filename()) out = out.parent_path();
    const std::string name = out.string();
    std::error_code ec;
    if (fs::exists(out, ec) && !fs::is_directory(out, ec)) throw InputError(name, "--out", "is not a directory");
    const fs::path record_file = out / "spec.json";
    const nlohmann::json record = spec_record(spec);
    const auto owned = owned_entries(out);
    const bool listed = owned && std::find(owned->begin(), owned->end(), "spec.json") != owned->end();
    if (fs::exists(record_file, ec)) {
        if (!listed && !unlisted_record_matches(record_file, record))
            throw InputError(name, "--out",
                             "is neither empty nor a campaign (no " + std::string(kOwnedList) +
                                 " list naming its spec.json): refusing to write into it");
        if (listed && read_json(record_file) != record)
            throw InputError(name, "--out",
                             "holds a campaign of another spec, seed or size (" + record_file.string() +
                                 "); give another directory");
    } else if (fs::exists(out, ec) && !only_a_campaign_starting(out)) {
        throw InputError(name, "--out",
                         "is neither empty nor a campaign (no " + std::string(kOwnedList) +
                             " list naming its spec.json): refusing to write into it");
    }
    fs::create_directories(out);
    record_owned(out, campaign_entries());
    fs::create_directories(out / "sequences");
    if (!fs::exists(record_file, ec)) write_shared_json(record_file, record);
    return out;
}

bool finished(const fs::path& out, int index) {
    std::error_code ec;
    return fs::exists(out / sequence_directory(index) / "manifest.json", ec);
}

}  // namespace

std::string sequence_directory(int index) {
    char name[32];
    std::snprintf(name, sizeof name, "sequences/%06d", index);
    return name;
}

CampaignSummary run_campaign(const CampaignSpec& spec, const CampaignOptions& options) {
    if (options.shards < 1 || options.shard < 0 || options.shard >= options.shards)
        throw InputError("--shard", "--shard", "shard " + std::to_string(options.shard) + " of " +
                                                   std::to_string(options.shards) + " does not exist");
    CampaignSummary summary;
    summary.out_dir = prepared_campaign_dir(spec, options.out_dir);
    const fs::path& out = summary.out_dir;

    std::vector<int> share;
    for (int i = options.shard; i < spec.sequences; i += options.shards) share.push_back(i);
    summary.in_share = static_cast<int>(share.size());
    int unfinished = 0;
    for (const int i : share) unfinished += !finished(out, i);
    summary.already_done = summary.in_share - unfinished;

    using Clock = std::chrono::steady_clock;
    const auto started = Clock::now();
    CampaignProgress progress;
    progress.sequences_in_share = summary.in_share;
    progress.sequences_done = summary.already_done;
    progress.frames = spec.frames;
    for (const int i : share) {
        if (finished(out, i)) continue;
        if (options.stop && options.stop->load()) {
            summary.interrupted = true;
            break;
        }
        const SampledSequence sampled = sample_sequence(spec, i);
        const fs::path scenario_file = out / (sequence_directory(i) + ".json");
        write_json(scenario_file, sampled.scenario);
        sensor_model::DatasetOptions render;
        render.out_dir = out / sequence_directory(i);
        render.threads = options.threads;
        // A sequence an interrupted run left goes on where it stopped; a new one starts (asking
        // it to resume warned, for every new sequence, that there was nothing to resume).
        render.resume = fs::exists(staging_dir(render.out_dir));
        render.stop = options.stop;
        progress.sequence = i;
        render.progress = [&](int done, int) {
            ++progress.frames_rendered;
            progress.frame = done;
            progress.frames_left = static_cast<long long>(summary.in_share - progress.sequences_done) * spec.frames - done;
            progress.seconds = std::chrono::duration<double>(Clock::now() - started).count();
            if (!options.progress) return;
            CampaignProgress now = progress;
            now.sequences_done += done == spec.frames;  // the sequence's last frame finishes it
            options.progress(now);
        };
        const sensor_model::DatasetSummary rendered = sensor_model::render_dataset(sensor_model::load_scenario(scenario_file), render);
        if (rendered.interrupted) {
            summary.interrupted = true;
            break;
        }
        ++summary.rendered;
        ++progress.sequences_done;
    }
    summary.frames_rendered = progress.frames_rendered;
    summary.seconds = std::chrono::duration<double>(Clock::now() - started).count();
    for (int i = 0; i < spec.sequences; ++i) summary.campaign_done += finished(out, i);
    if (summary.campaign_done == spec.sequences) {
        write_shared_json(out / "campaign.json", campaign_index(spec, out));
        summary.index_written = true;
    }
    return summary;
}

}  // namespace ladarsim::campaign
