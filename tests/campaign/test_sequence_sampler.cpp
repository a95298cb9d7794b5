// Sequences drawn from a spec: every value inside its distribution's bounds, the draws of many
// sequences distributed as the spec says, a sequence the same whatever the campaign's size, and
// splits that cover every sequence in the given shares.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>

#include <catch2/catch.hpp>

#include "../support/scratch_dir.h"
#include "ladarsim/campaign/campaign_spec.h"
#include "ladarsim/campaign/sequence_sampler.h"

namespace {

using namespace ladarsim;
using namespace ladarsim::campaign;

const std::string kModels = std::string(LADARSIM_SOURCE_DIR) + "/assets/models/";

CampaignSpec spec_of(const test::ScratchDir& dir, nlohmann::json document) {
    std::ofstream(dir / "spec.json") << document.dump();
    return read_campaign_spec(dir / "spec.json");
}

nlohmann::json many_draws_spec(int sequences) {
    nlohmann::json spec = nlohmann::json::parse(R"({
        "frames": 1, "seed": 11,
        "splits": {"train": 0.6, "val": 0.3, "test": 0.1},
        "sensor": {"choice": [{"preset": "paper_ladar"}, {"preset": "velodyne_vlp16"}], "weights": [3, 1]},
        "sensor_height_m": {"uniform": [2, 30]},
        "atmosphere": {"visibility_km": {"log_uniform": [1, 100]}},
        "objects": [{"class": "drone", "count": {"uniform": [0, 3]},
                     "range_m": {"uniform": [100, 2000]}, "bearing_deg": {"uniform": [-10, 10]},
                     "altitude_m": {"uniform": [5, 100]},
                     "trajectory": {"choice": ["approach", "straight", "hover"], "weights": [2, 1, 1]},
                     "speed_mps": {"uniform": [2, 20]}, "heading_deg": {"uniform": [0, 360]}}]
    })");
    spec["sequences"] = sequences;
    spec["objects"][0]["model"] = kModels + "quadcopter.glb";
    return spec;
}

}  // namespace

TEST_CASE("Sampled values lie within their distributions and follow them over many sequences", "[campaign]") {
    const test::ScratchDir dir;
    constexpr int kSequences = 4000;
    const CampaignSpec spec = spec_of(dir, many_draws_spec(kSequences));
    std::map<std::string, int> presets, trajectories;
    std::map<long long, int> counts;
    std::vector<double> heights, visibilities, ranges, speeds;
    for (int i = 0; i < kSequences; ++i) {
        const SampledSequence s = sample_sequence(spec, i);
        const nlohmann::json& d = s.sampled;
        ++presets[d["sensor"]["preset"].get<std::string>()];
        heights.push_back(d["sensor_height_m"].get<double>());
        visibilities.push_back(d["atmosphere"]["visibility_km"].get<double>());
        ++counts[static_cast<long long>(d["objects"].size())];
        for (const auto& o : d["objects"]) {
            ranges.push_back(o["range_m"].get<double>());
            ++trajectories[o["trajectory"].get<std::string>()];
            REQUIRE(o["bearing_deg"].get<double>() >= -10.0);
            REQUIRE(o["bearing_deg"].get<double>() <= 10.0);
            REQUIRE(o["altitude_m"].get<double>() >= 5.0);
            REQUIRE(o["altitude_m"].get<double>() <= 100.0);
            if (o["trajectory"] != "hover") speeds.push_back(o["speed_mps"].get<double>());
            else REQUIRE_FALSE(o.contains("speed_mps"));
        }
        // The scenario holds what was drawn: the sensor at its height, cued to the first drone.
        REQUIRE(s.scenario["sensor"]["position_m"][2] == d["sensor_height_m"]);
        REQUIRE(s.scenario["render"]["frames"] == 1);
        if (!d["objects"].empty()) REQUIRE(s.scenario["sensor"]["cue_object"] == 1);
    }
    const auto within = [](const std::vector<double>& v, double lo, double hi) {
        return std::all_of(v.begin(), v.end(), [&](double x) { return x >= lo && x <= hi; });
    };
    const auto mean = [](const std::vector<double>& v) {
        double sum = 0.0;
        for (const double x : v) sum += x;
        return sum / static_cast<double>(v.size());
    };
    const auto median = [](std::vector<double> v) {
        std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
        return v[v.size() / 2];
    };
    CHECK(within(heights, 2.0, 30.0));
    CHECK(within(visibilities, 1.0, 100.0));
    CHECK(within(ranges, 100.0, 2000.0));
    CHECK(within(speeds, 2.0, 20.0));
    // A uniform's mean is the middle within 4 standard errors; a log-uniform's median the
    // geometric middle; a choice's frequencies its weights.
    const auto standard_error = [](double lo, double hi, std::size_t n) { return (hi - lo) / std::sqrt(12.0 * double(n)); };
    CHECK(std::abs(mean(heights) - 16.0) < 4.0 * standard_error(2.0, 30.0, heights.size()));
    CHECK(std::abs(mean(ranges) - 1050.0) < 4.0 * standard_error(100.0, 2000.0, ranges.size()));
    CHECK(std::abs(std::log10(median(visibilities)) - 1.0) < 0.05);
    CHECK(std::abs(presets["paper_ladar"] / double(kSequences) - 0.75) < 0.03);
    const double objects = double(ranges.size());
    CHECK(std::abs(trajectories["approach"] / objects - 0.5) < 0.03);
    CHECK(std::abs(trajectories["hover"] / objects - 0.25) < 0.03);
    // A whole-number uniform reaches both ends equally often.
    REQUIRE(counts.size() == 4);
    for (const auto& [count, n] : counts) CHECK(std::abs(n / double(kSequences) - 0.25) < 0.03);
}

TEST_CASE("A sequence's draws depend on the campaign seed and its index only", "[campaign]") {
    const test::ScratchDir small_dir, large_dir;
    const CampaignSpec small = spec_of(small_dir, many_draws_spec(4));
    const CampaignSpec large = spec_of(large_dir, many_draws_spec(1000));
    for (int i = 0; i < 4; ++i) {
        CHECK(sample_sequence(small, i).scenario == sample_sequence(large, i).scenario);
        CHECK(sample_sequence(small, i).sampled == sample_sequence(large, i).sampled);
    }
    CHECK(sample_sequence(small, 0).scenario != sample_sequence(small, 1).scenario);
    nlohmann::json reseeded = many_draws_spec(4);
    reseeded["seed"] = 12;
    const CampaignSpec other = spec_of(large_dir, reseeded);
    CHECK(sample_sequence(other, 0).sampled != sample_sequence(small, 0).sampled);
}

TEST_CASE("Splits cover every sequence in the shares given, by largest remainder", "[campaign]") {
    const test::ScratchDir dir;
    for (const int n : {1, 6, 7, 10, 333}) {
        const CampaignSpec spec = spec_of(dir, many_draws_spec(n));
        const std::vector<std::string> splits = sequence_splits(spec);
        REQUIRE(splits.size() == static_cast<std::size_t>(n));
        std::map<std::string, int> count;
        for (const auto& s : splits) ++count[s];
        CHECK(count["train"] + count["val"] + count["test"] == n);
        CHECK(std::abs(count["train"] - 0.6 * n) < 1.0);
        CHECK(std::abs(count["val"] - 0.3 * n) < 1.0);
        CHECK(std::abs(count["test"] - 0.1 * n) < 1.0);
    }
}
