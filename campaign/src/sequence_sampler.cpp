#include "ladarsim/campaign/sequence_sampler.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>

#include "ladarsim/campaign/campaign_random.h"

namespace ladarsim::campaign {

namespace {

/// The draws of one sequence, each named by what it draws.
class SequenceDraws {
public:
    SequenceDraws(std::uint64_t seed, int index) : seed_(seed), index_(static_cast<std::uint64_t>(index)) {}
    double uniform(const std::string& what) const { return campaign_uniform(seed_, index_, what); }
    nlohmann::json operator()(const Distribution& d, const std::string& what) const { return d.draw(uniform(what)); }
    std::size_t index_of(const Distribution& d, const std::string& what) const { return d.draw_index(uniform(what)); }

private:
    std::uint64_t seed_;
    std::uint64_t index_;
};

bool is_target(const std::string& object_class) {
    return object_class == "drone" || object_class == "bird" || object_class == "plane";
}

nlohmann::json vec3(const std::array<double, 3>& v) { return {v[0], v[1], v[2]}; }

/// One object of `group` (its k-th), numbered `id`: the scenario's object and what was drawn.
std::pair<nlohmann::json, nlohmann::json> sample_object(const ObjectGroup& group, int k, std::uint32_t id,
                                                        const std::array<double, 3>& sensor_m, const SequenceDraws& draw) {
    const std::string p = group.path + "#" + std::to_string(k) + ".";
    nlohmann::json object = {{"id", id}, {"class", group.object_class}, {"model", group.model_file.string()}};
    nlohmann::json sampled = {{"id", id}, {"class", group.object_class}, {"model", group.model}};
    const auto take = [&](const std::optional<Distribution>& d, const char* key) -> std::optional<nlohmann::json> {
        if (!d) return std::nullopt;
        nlohmann::json v = draw(*d, p + key);
        sampled[key] = v;
        return v;
    };
    if (auto v = take(group.size_m, "size_m")) object["size_m"] = *v;
    if (auto v = take(group.reflectance, "reflectance")) object["reflectance"] = *v;
    if (auto v = take(group.mor_m, "mor_m")) object["medium"] = {{"mor_m", *v}};
    if (auto v = take(group.extinction_per_km, "extinction_per_km")) object["medium"]["extinction_per_km"] = *v;
    if (auto v = take(group.backscatter_per_km_sr, "backscatter_per_km_sr")) object["medium"]["backscatter_per_km_sr"] = *v;

    const double range = *take(group.range_m, "range_m");
    const double bearing = *take(group.bearing_deg, "bearing_deg");
    const double altitude = *take(group.altitude_m, "altitude_m");
    const double b = bearing * std::numbers::pi / 180.0;
    const std::array<double, 3> start = {range * std::cos(b), range * std::sin(b), altitude};
    const std::string type = take(group.trajectory, "trajectory")->get<std::string>();

    nlohmann::json trajectory = {{"type", type}};
    if (type == "fixed") {
        trajectory["position_m"] = vec3(start);
        if (auto v = take(group.heading_deg, "heading_deg")) trajectory["yaw_deg"] = *v;
    } else if (type == "approach") {
        trajectory["start_m"] = vec3(start);
        trajectory["towards_m"] = vec3(sensor_m);
        trajectory["speed_mps"] = *take(group.speed_mps, "speed_mps");
    } else if (type == "straight" || type == "winding") {
        const double speed = *take(group.speed_mps, "speed_mps");
        const double heading = take(group.heading_deg, "heading_deg")->get<double>() * std::numbers::pi / 180.0;
        trajectory["start_m"] = vec3(start);
        trajectory["velocity_mps"] = {speed * std::cos(heading), speed * std::sin(heading), 0.0};
        if (type == "winding") {
            trajectory["amplitude_m"] = *take(group.amplitude_m, "amplitude_m");
            trajectory["period_s"] = *take(group.period_s, "period_s");
        }
    } else {  // hover
        trajectory["centre_m"] = vec3(start);
        if (auto v = take(group.radius_m, "radius_m")) trajectory["radius_m"] = *v;
        if (auto v = take(group.period_s, "period_s")) trajectory["period_s"] = *v;
    }
    object["trajectory"] = std::move(trajectory);
    return {std::move(object), std::move(sampled)};
}

}  // namespace

SampledSequence sample_sequence(const CampaignSpec& spec, int index) {
    const SequenceDraws draw(spec.seed, index);
    SampledSequence s;
    s.index = index;
    s.seed = campaign_bits63(spec.seed, static_cast<std::uint64_t>(index), "render.seed");
    nlohmann::json& scenario = s.scenario;
    nlohmann::json& sampled = s.sampled;

    const std::size_t sensor_index = draw.index_of(spec.sensor, "sensor");
    nlohmann::json sensor = spec.sensor.values()[sensor_index];
    const double height = draw(spec.sensor_height_m, "sensor_height_m").get<double>();
    const std::array<double, 3> sensor_m = {0.0, 0.0, height};
    sensor["position_m"] = vec3(sensor_m);
    sampled["sensor"] = {{"choice", sensor_index}};
    for (const char* key : {"preset", "file"})
        if (sensor.contains(key)) sampled["sensor"][key] = sensor[key];
    // A sensor file is named relative to the spec; the scenario is written elsewhere.
    if (sensor.contains("file"))
        sensor["file"] = std::filesystem::absolute(spec.file.parent_path() / sensor["file"].get<std::string>())
                             .lexically_normal()
                             .string();
    sampled["sensor_height_m"] = height;

    scenario["render"] = spec.render;
    scenario["render"]["frames"] = spec.frames;
    scenario["render"]["seed"] = s.seed;

    nlohmann::json atmosphere = nlohmann::json::object();
    for (const auto& [key, d] : spec.atmosphere) atmosphere[key] = draw(d, "atmosphere." + key);
    if (!atmosphere.empty()) scenario["atmosphere"] = atmosphere;
    sampled["atmosphere"] = atmosphere;

    nlohmann::json objects = nlohmann::json::array(), sampled_objects = nlohmann::json::array();
    std::uint32_t next_id = 1, cue = 0;
    for (const ObjectGroup& group : spec.groups) {
        const int count = static_cast<int>(draw(group.count, group.path + ".count").get<long long>());
        for (int k = 0; k < count; ++k) {
            auto [object, values] = sample_object(group, k, next_id, sensor_m, draw);
            if (cue == 0 && is_target(group.object_class)) cue = next_id;
            objects.push_back(std::move(object));
            sampled_objects.push_back(std::move(values));
            ++next_id;
        }
    }
    if (cue != 0) sensor["cue_object"] = cue;
    scenario["sensor"] = std::move(sensor);
    if (!objects.empty()) scenario["objects"] = std::move(objects);
    sampled["objects"] = std::move(sampled_objects);

    sampled["background"] = nullptr;
    if (!spec.backgrounds.empty() && draw.uniform("background") < spec.background_probability) {
        const std::size_t m = draw.index_of(spec.background_choice, "background.map");
        const BackgroundChoice& choice = spec.backgrounds[m];
        nlohmann::json offset = nlohmann::json::array();
        for (std::size_t k = 0; k < 3; ++k)
            offset.push_back(draw(choice.offset_m[k], "background.map.offset_m[" + std::to_string(k) + "]"));
        const nlohmann::json heading = draw(choice.heading_deg, "background.map.heading_deg");
        nlohmann::json background = choice.fixed_keys;
        background["file"] = choice.map_file.string();
        background["offset_m"] = offset;
        background["heading_deg"] = heading;
        scenario["background"] = std::move(background);
        sampled["background"] = {{"choice", m}, {"file", choice.file}, {"offset_m", offset}, {"heading_deg", heading}};
    }
    return s;
}

std::vector<std::string> sequence_splits(const CampaignSpec& spec) {
    const int n = spec.sequences;
    const std::array<std::pair<const char*, double>, 3> shares = {{{"train", spec.train}, {"val", spec.val}, {"test", spec.test}}};
    // Largest remainder: each split gets floor(share * n), the rest go to the largest fractions.
    std::array<int, 3> counts{};
    std::array<double, 3> remainders{};
    int given = 0;
    for (std::size_t k = 0; k < 3; ++k) {
        const double exact = shares[k].second * n;
        counts[k] = static_cast<int>(std::floor(exact));
        remainders[k] = exact - counts[k];
        given += counts[k];
    }
    std::array<std::size_t, 3> by_remainder = {0, 1, 2};
    std::stable_sort(by_remainder.begin(), by_remainder.end(),
                     [&](std::size_t a, std::size_t b) { return remainders[a] > remainders[b]; });
    for (std::size_t k = 0; given < n; ++k, ++given) ++counts[by_remainder[k % 3]];

    std::vector<int> order(static_cast<std::size_t>(n));
    std::iota(order.begin(), order.end(), 0);
    std::vector<double> key(order.size());
    for (int i = 0; i < n; ++i) key[static_cast<std::size_t>(i)] = campaign_uniform(spec.seed, static_cast<std::uint64_t>(i), "split");
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return key[static_cast<std::size_t>(a)] < key[static_cast<std::size_t>(b)]; });
    std::vector<std::string> splits(order.size());
    std::size_t next = 0;
    for (std::size_t k = 0; k < 3; ++k)
        for (int c = 0; c < counts[k]; ++c) splits[static_cast<std::size_t>(order[next++])] = shares[k].first;
    return splits;
}

}  // namespace ladarsim::campaign
