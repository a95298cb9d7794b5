#include "ladarsim/campaign/campaign_index.h"

#include <map>

#include "ladarsim/campaign/campaign_run.h"
#include "ladarsim/campaign/sequence_sampler.h"
#include "ladarsim/dataset/dataset_directory.h"
#include "ladarsim/dataset/frame_io.h"
#include "ladarsim/core/input_error.h"

namespace ladarsim::campaign {

namespace {

namespace fs = std::filesystem;

/// Returns by class over a sequence's frames: each object's by the class it was drawn with.
std::map<std::string, std::uint64_t> returns_by_class(const fs::path& dataset, const nlohmann::json& objects) {
    std::map<std::uint32_t, std::string> class_of = {{0u, "background"}, {kNoObject, "false_alarm"}};
    for (const auto& o : objects) class_of[o.at("id").get<std::uint32_t>()] = o.at("class").get<std::string>();
    std::map<std::string, std::uint64_t> counts;
    for (const auto& file : frame_pcd_files(dataset))
        for (const Return& r : read_frame_pcd(file)) ++counts[class_of.at(r.object_id)];
    return counts;
}

}  // namespace

nlohmann::json campaign_index(const CampaignSpec& spec, const fs::path& dir) {
    const std::vector<std::string> splits = sequence_splits(spec);
    nlohmann::json sequences = nlohmann::json::array();
    std::map<std::string, std::uint64_t> totals;
    std::map<std::string, int> split_counts = {{"train", 0}, {"val", 0}, {"test", 0}};
    for (int i = 0; i < spec.sequences; ++i) {
        const SampledSequence s = sample_sequence(spec, i);
        const auto counts = returns_by_class(dir / sequence_directory(i), s.sampled.at("objects"));
        for (const auto& [c, n] : counts) totals[c] += n;
        ++split_counts[splits[static_cast<std::size_t>(i)]];
        sequences.push_back({{"id", i},
                             {"directory", sequence_directory(i)},
                             {"scenario", sequence_directory(i) + ".json"},
                             {"split", splits[static_cast<std::size_t>(i)]},
                             {"seed", s.seed},
                             {"frames", spec.frames},
                             {"sampled", s.sampled},
                             {"returns_by_class", counts}});
    }
    return {{"software", software_json()},
            {"spec_file", fs::absolute(spec.file).lexically_normal().string()},
            {"spec", spec.source},
            {"seed", spec.seed},
            {"frames", spec.frames},
            {"splits", split_counts},
            {"returns_by_class", totals},
            {"sequences", std::move(sequences)}};
}

bool is_campaign(const fs::path& dir) {
    std::error_code ec;
    return fs::is_regular_file(dir / "campaign.json", ec);
}

std::vector<IndexedSequence> read_campaign_index(const fs::path& dir) {
    const fs::path file = dir / "campaign.json";
    const nlohmann::json index = read_json(file);
    const std::string name = file.string();
    if (!index.is_object() || !index.contains("sequences") || !index["sequences"].is_array())
        throw InputError(name, "sequences", "missing: not a campaign's index");
    std::vector<IndexedSequence> sequences;
    for (std::size_t i = 0; i < index["sequences"].size(); ++i) {
        const nlohmann::json& entry = index["sequences"][i];
        const std::string path = "sequences[" + std::to_string(i) + "]";
        // The index has more keys than a reader of its sequences needs: read those, ignore the rest.
        if (!entry.is_object()) throw InputError(name, path, "expected an object");
        for (const char* key : {"id", "directory", "split"})
            if (!entry.contains(key)) throw InputError(name, path + "." + key, "required field is missing");
        if (!entry["id"].is_number_integer() || !entry["directory"].is_string() || !entry["split"].is_string())
            throw InputError(name, path, "id must be a whole number, directory and split strings");
        IndexedSequence s;
        s.id = entry["id"].get<int>();
        s.directory = fs::absolute(dir / entry["directory"].get<std::string>()).lexically_normal();
        s.split = entry["split"].get<std::string>();
        std::error_code ec;
        if (!fs::is_directory(s.directory, ec))
            throw InputError(name, path + ".directory", "no such directory: " + s.directory.string());
        sequences.push_back(std::move(s));
    }
    return sequences;
}

}  // namespace ladarsim::campaign
