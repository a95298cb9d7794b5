#include "ladarsim/campaign/campaign_spec.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "ladarsim/core/input_error.h"
#include "ladarsim/core/json_file.h"
#include "ladarsim/scene/object_class.h"
#include "ladarsim/sensor_model/render/scenario.h"

namespace ladarsim::campaign {

namespace {

namespace fs = std::filesystem;

constexpr double kMaxDistance_m = 1e6;
constexpr int kMaxCount = 1000;
constexpr int kMaxSequences = 10'000'000;

std::string index_path(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

/// A file named by the spec, relative to the spec's folder; refused when it is not there.
fs::path existing_file(SpecFields& f, const std::string& key, const fs::path& spec_dir) {
    const fs::path file = (spec_dir / f.string(key)).lexically_normal();
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) f.fail(key, "no such file: " + file.string());
    return fs::absolute(file);
}

/// The trajectory types `trajectory` can give.
std::set<std::string> possible_types(const Distribution& trajectory) {
    std::set<std::string> types;
    for (const auto& v : trajectory.values()) types.insert(v.get<std::string>());
    return types;
}

/// A trajectory key: required when a type that needs it can be drawn, refused when no type that
/// uses it can (a key that does nothing is a mistake), else optional.
std::optional<Distribution> trajectory_key(SpecFields& g, const std::string& key, const std::set<std::string>& types,
                                           const std::set<std::string>& needing, const std::set<std::string>& using_it,
                                           double min, double max) {
    const auto any_of = [&](const std::set<std::string>& of) {
        return std::any_of(of.begin(), of.end(), [&](const std::string& t) { return types.count(t) > 0; });
    };
    if (!g.has(key)) {
        for (const auto& t : needing)
            if (types.count(t)) g.fail(key, "required: trajectory " + t + " can be drawn and needs it");
        return std::nullopt;
    }
    if (!any_of(needing) && !any_of(using_it)) {
        std::string list;
        for (const auto& t : types) list += (list.empty() ? "" : ", ") + t;
        g.fail(key, "no trajectory type this group draws (" + list + ") uses it");
    }
    return Distribution::number(g, key, min, max);
}

ObjectGroup read_group(SpecFields& g, const fs::path& spec_dir) {
    ObjectGroup group;
    group.path = g.path_of("");
    group.path.pop_back();  // path_of("") ends in '.'
    group.object_class = g.string("class");
    const auto object_class = scene::object_class_from_string(group.object_class);
    if (!object_class || *object_class == scene::ObjectClass::background)
        g.fail("class", "\"" + group.object_class + "\" is not one of: drone, bird, plane, building, terrain, tree, cloud");
    group.model = g.string("model");
    group.model_file = existing_file(g, "model", spec_dir);
    group.count = Distribution::number(g, "count", 0, kMaxCount, 1, true);
    if (g.has("size_m")) group.size_m = Distribution::number(g, "size_m", 1e-6, kMaxDistance_m);
    if (g.has("reflectance")) group.reflectance = Distribution::number(g, "reflectance", 0.0, 1.0);
    if (g.has("medium")) {
        SpecFields m(g.object("medium"), g.file(), g.path_of("medium"));
        if (m.has("mor_m")) {
            if (m.has("extinction_per_km")) m.fail("mor_m", "give mor_m or extinction_per_km, not both");
            group.mor_m = Distribution::number(m, "mor_m", 1.0, 1e6);
        } else {
            group.extinction_per_km = Distribution::number(m, "extinction_per_km", 1e-6, 1e6);
            group.backscatter_per_km_sr = Distribution::number(m, "backscatter_per_km_sr", 0.0, 1e6);
        }
        m.reject_unknown_keys();
    }
    group.range_m = Distribution::number(g, "range_m", 0.0, kMaxDistance_m);
    group.bearing_deg = Distribution::number(g, "bearing_deg", -360.0, 360.0, 0.0);
    group.altitude_m = Distribution::number(g, "altitude_m", -kMaxDistance_m, kMaxDistance_m, 0.0);
    group.trajectory = g.has("trajectory")
                           ? Distribution::value(g, "trajectory",
                                                 [&](const nlohmann::json& v, const std::string& path) {
                                                     if (!v.is_string() ||
                                                         std::find(kTrajectoryTypes.begin(), kTrajectoryTypes.end(),
                                                                   v.get<std::string>()) == kTrajectoryTypes.end())
                                                         throw InputError(g.file(), path,
                                                                          v.dump() + " is not one of: fixed, approach, "
                                                                                     "straight, winding, hover");
                                                 })
                           : Distribution::fixed("fixed");
    const std::set<std::string> types = possible_types(group.trajectory);
    group.speed_mps = trajectory_key(g, "speed_mps", types, {"approach", "straight", "winding"}, {}, 1e-3, 1e4);
    group.heading_deg = trajectory_key(g, "heading_deg", types, {"straight", "winding"}, {"fixed"}, -360.0, 360.0);
    group.amplitude_m = trajectory_key(g, "amplitude_m", types, {"winding"}, {}, 0.0, kMaxDistance_m);
    group.period_s = trajectory_key(g, "period_s", types, {"winding"}, {"hover"}, 1e-3, 1e6);
    group.radius_m = trajectory_key(g, "radius_m", types, {}, {"hover"}, 0.0, kMaxDistance_m);
    g.reject_unknown_keys();
    return group;
}

/// The scenario's background keys a map entry passes on as given (docs/scenario.md).
const std::set<std::string>& passed_background_keys() {
    static const std::set<std::string> keys = {"scale", "reflectance", "reflectance_at_max_intensity",
                                               "reflectance_per_intensity", "neighbours", "scanner_position_m"};
    return keys;
}

BackgroundChoice read_background_choice(const nlohmann::json& value, const std::string& file, const std::string& path,
                                        const fs::path& spec_dir) {
    SpecFields m(value, file, path);
    BackgroundChoice c;
    c.file = m.string("file");
    c.map_file = existing_file(m, "file", spec_dir);
    if (m.has("offset_m")) {
        const nlohmann::json& offset = m.array("offset_m");
        if (offset.size() != 3) m.fail("offset_m", "expected [x, y, z], each a number or a distribution");
        for (std::size_t k = 0; k < 3; ++k) {
            // Each coordinate read as a key of its own, so that errors name it "offset_m[k]".
            const std::string key = index_path("offset_m", k);
            const nlohmann::json holder = {{key, offset[k]}};
            SpecFields coordinate(holder, file, path);
            c.offset_m.push_back(Distribution::number(coordinate, key, -1e9, 1e9));
        }
    } else {
        c.offset_m.assign(3, Distribution::fixed(0.0));
    }
    c.heading_deg = Distribution::number(m, "heading_deg", -360.0, 360.0, 0.0);
    c.fixed_keys = nlohmann::json::object();
    for (const auto& [key, v] : value.items())
        if (passed_background_keys().count(key)) c.fixed_keys[key] = m.raw(key);
    m.reject_unknown_keys();
    return c;
}

/// Refuses a sensor entry, or render keys, that the scenario reader refuses, naming the spec's key.
void check_with_scenario_reader(const CampaignSpec& spec, const fs::path& spec_dir) {
    for (std::size_t i = 0; i < spec.sensor.values().size(); ++i) {
        const std::string entry_path =
            spec.sensor.kind() == Distribution::Kind::choice ? index_path("sensor.choice", i) : "sensor";
        nlohmann::json sensor = spec.sensor.values()[i];
        for (const char* key : {"position_m", "cue_object"})
            if (sensor.contains(key))
                throw InputError(spec.file.string(), entry_path + "." + key,
                                 "set by the campaign (the sensor stands at sensor_height_m, cued to the first target)");
        sensor["position_m"] = {0.0, 0.0, 2.0};
        nlohmann::json render = spec.render;
        render["frames"] = 1;
        try {
            sensor_model::load_scenario(nlohmann::json{{"sensor", sensor}, {"render", render}}, spec_dir);
        } catch (const InputError& e) {
            const std::string& field = e.field();
            const bool in_sensor = field.rfind("sensor", 0) == 0;
            throw InputError(spec.file.string(), in_sensor ? entry_path + field.substr(6) : field, e.problem());
        }
    }
}

}  // namespace

CampaignSpec read_campaign_spec(const fs::path& file, const SpecOverrides& overrides) {
    CampaignSpec spec;
    spec.file = file;
    spec.source = read_json(file);
    if (overrides.sequences) spec.source["sequences"] = *overrides.sequences;
    if (overrides.frames) spec.source["frames"] = *overrides.frames;
    if (overrides.seed) spec.source["seed"] = *overrides.seed;
    const std::string name = file.string();
    const fs::path spec_dir = file.parent_path();
    SpecFields top(spec.source, name, "");

    spec.sequences = static_cast<int>(top.integer("sequences", 1, kMaxSequences));
    spec.frames = static_cast<int>(top.integer("frames", 1, 10'000'000));
    spec.seed = static_cast<std::uint64_t>(top.integer("seed", 0, std::numeric_limits<long long>::max(), 1));

    if (top.has("splits")) {
        SpecFields s(top.object("splits"), name, "splits");
        spec.train = s.number("train", 0.0, 1.0, 0.0);
        spec.val = s.number("val", 0.0, 1.0, 0.0);
        spec.test = s.number("test", 0.0, 1.0, 0.0);
        s.reject_unknown_keys();
        const double sum = spec.train + spec.val + spec.test;
        if (std::abs(sum - 1.0) > 1e-9)
            s.fail("", "the shares of train, val and test sum to " + nlohmann::json(sum).dump() + ", not 1");
    }

    spec.sensor = Distribution::value(top, "sensor", [&](const nlohmann::json& v, const std::string& path) {
        if (!v.is_object()) throw InputError(name, path, "expected a sensor object ({\"preset\": ...} or {\"file\": ...})");
    });
    spec.sensor_height_m = Distribution::number(top, "sensor_height_m", -kMaxDistance_m, kMaxDistance_m, 2.0);
    if (top.has("render")) {
        spec.render = top.object("render");
        for (const char* key : {"frames", "seed"})
            if (spec.render.contains(key))
                throw InputError(name, std::string("render.") + key,
                                 "set by the campaign (its frames; each sequence's seed is drawn from the campaign seed)");
    } else {
        spec.render = nlohmann::json::object();
    }

    if (top.has("atmosphere")) {
        SpecFields a(top.object("atmosphere"), name, "atmosphere");
        if (a.has("visibility_km")) spec.atmosphere.emplace_back("visibility_km", Distribution::number(a, "visibility_km", 0.01, 1e6));
        if (a.has("daylight"))
            spec.atmosphere.emplace_back("daylight", Distribution::value(a, "daylight", [&](const nlohmann::json& v, const std::string& path) {
                                             if (!v.is_boolean()) throw InputError(name, path, v.dump() + " is not true or false");
                                         }));
        if (a.has("solar_irradiance_w_m2_nm"))
            spec.atmosphere.emplace_back("solar_irradiance_w_m2_nm", Distribution::number(a, "solar_irradiance_w_m2_nm", 0.0, 10.0));
        if (a.has("background_reflectance"))
            spec.atmosphere.emplace_back("background_reflectance", Distribution::number(a, "background_reflectance", 0.0, 1.0));
        a.reject_unknown_keys();
    }

    if (top.has("objects")) {
        const nlohmann::json& objects = top.array("objects");
        for (std::size_t i = 0; i < objects.size(); ++i) {
            SpecFields g(objects[i], name, index_path("objects", i));
            spec.groups.push_back(read_group(g, spec_dir));
        }
    }
    long long most_objects = 0;
    for (const auto& g : spec.groups) most_objects += static_cast<long long>(g.count.hi());
    if (most_objects > kMaxCount)
        top.fail("objects", "up to " + std::to_string(most_objects) + " objects a sequence; at most " +
                                std::to_string(kMaxCount));

    if (top.has("background")) {
        SpecFields b(top.object("background"), name, "background");
        spec.background_probability = b.number("probability", 0.0, 1.0, 1.0);
        spec.background_choice = Distribution::value(b, "map", [&](const nlohmann::json& v, const std::string& path) {
            spec.backgrounds.push_back(read_background_choice(v, name, path, spec_dir));
        });
        b.reject_unknown_keys();
    }
    top.reject_unknown_keys();
    check_with_scenario_reader(spec, spec_dir);
    return spec;
}

}  // namespace ladarsim::campaign
