#include "ladarsim/scene/scene_file.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ladarsim/core/input_error.h"
#include "ladarsim/scene/animation.h"
#include "ladarsim/scene/background_map.h"
#include "ladarsim/scene/gltf_loader.h"

namespace ladarsim::scene {

namespace {

namespace fs = std::filesystem;

// Bounds that only catch typos (a missing decimal point, degrees for metres), not physics.
constexpr double kMaxDistance_m = 1e5;
constexpr double kMaxSpeed_mps = 1e4;
constexpr double kMaxTime_s = 1e9;
constexpr double kMaxScale = 1e6;  // a model in micrometres still fits

std::string index_path(const std::string& array_path, std::size_t i) {
    return array_path + "[" + std::to_string(i) + "]";
}

/// A number in (0, max]: periods and speeds where zero would divide or mean nothing.
double positive(JsonFields& f, const std::string& key, double max) {
    const double x = f.number(key, 0.0, max);
    if (x == 0.0) f.fail(key, "must be greater than 0");
    return x;
}

double positive(JsonFields& f, const std::string& key, double max, double fallback) {
    return f.has(key) ? positive(f, key, max) : fallback;
}

/// `choice` for a key that has no default.
std::string required_choice(JsonFields& f, const std::string& key, const std::vector<std::string>& allowed) {
    if (!f.has(key)) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        f.fail(key, "required field is missing; one of: " + list);
    }
    return f.choice(key, allowed, "");
}

Eigen::Quaterniond read_orientation(JsonFields& f) {
    return orientation_from_ypr_deg(f.number("yaw_deg", -360.0, 360.0, 0.0), f.number("pitch_deg", -90.0, 90.0, 0.0),
                                    f.number("roll_deg", -180.0, 180.0, 0.0));
}

Trajectory read_keyframes(JsonFields& t) {
    const Interpolation interpolation =
        t.choice("interpolation", {"linear", "smooth"}, "linear") == "smooth" ? Interpolation::smooth
                                                                              : Interpolation::linear;
    const nlohmann::json& keys_json = t.array("keys");
    if (keys_json.empty()) t.fail("keys", "needs at least one keyframe");
    const std::string keys_path = t.path_of("keys");
    std::vector<Keyframe> keys;
    for (std::size_t j = 0; j < keys_json.size(); ++j) {
        JsonFields k(keys_json[j], t.file(), index_path(keys_path, j));
        Keyframe key;
        key.time_s = k.number("time_s", -kMaxTime_s, kMaxTime_s);
        if (!keys.empty() && !(key.time_s > keys.back().time_s)) {
            k.fail("time_s", "must be later than the previous key's " + nlohmann::json(keys.back().time_s).dump() + " s");
        }
        key.pose.position = k.vec3("position_m");
        key.pose.orientation = read_orientation(k);
        k.reject_unknown_keys();
        keys.push_back(key);
    }
    return Trajectory::keyframes(std::move(keys), interpolation);
}

}  // namespace

Trajectory read_trajectory(JsonFields& t) {
    const std::string type =
        required_choice(t, "type", {"fixed", "straight", "approach", "winding", "hover", "keyframes"});
    Trajectory trajectory = Trajectory::fixed(Pose{});
    if (type == "fixed") {
        Pose pose;
        pose.position = t.vec3("position_m");
        pose.orientation = read_orientation(t);
        trajectory = Trajectory::fixed(pose);
    } else if (type == "straight") {
        trajectory = Trajectory::straight(t.vec3("start_m"), t.vec3("velocity_mps"));
    } else if (type == "approach") {
        const Eigen::Vector3d start = t.vec3("start_m");
        const Eigen::Vector3d towards = t.vec3("towards_m");
        const double speed_mps = positive(t, "speed_mps", kMaxSpeed_mps);
        if (towards == start) t.fail("towards_m", "equals start_m, so there is no direction to fly");
        trajectory = Trajectory::straight(start, speed_mps * (towards - start).normalized());
    } else if (type == "winding") {
        const Eigen::Vector3d start = t.vec3("start_m");
        const Eigen::Vector3d velocity = t.vec3("velocity_mps");
        const double amplitude_m = t.number("amplitude_m", 0.0, kMaxDistance_m);
        trajectory = Trajectory::winding(start, velocity, amplitude_m, positive(t, "period_s", kMaxTime_s));
    } else if (type == "hover") {
        const Eigen::Vector3d centre = t.vec3("centre_m");
        const double radius_m = t.number("radius_m", 0.0, kMaxDistance_m, 0.0);
        trajectory = Trajectory::hover(centre, radius_m, positive(t, "period_s", kMaxTime_s, 10.0));
    } else {
        trajectory = read_keyframes(t);
    }
    t.reject_unknown_keys();
    return trajectory;
}

namespace {

/// Names of the classes a scenario object may have: every class but the recorded background.
std::vector<std::string> object_class_names() {
    std::vector<std::string> names;
    for (int c = 0;; ++c) {
        const std::string_view name = to_string(static_cast<ObjectClass>(c));
        if (name == "unknown") break;
        if (name != to_string(ObjectClass::background)) names.emplace_back(name);
    }
    return names;
}

/// Loads each model file once, so objects that use the same file instance one mesh.
class ModelCache {
public:
    std::shared_ptr<const Model> get(const fs::path& file) {
        const fs::path key = fs::weakly_canonical(file);
        auto it = models_.find(key);
        if (it == models_.end()) it = models_.emplace(key, std::make_shared<const Model>(load_gltf(file))).first;
        return it->second;
    }

private:
    std::map<fs::path, std::shared_ptr<const Model>> models_;
};

/// Per-object reflectance: `reflectance` sets every material, then `materials` sets named ones;
/// `medium` turns every material into a volume (fog or cloud). Returns the shared model untouched
/// when there is nothing to override, else a private copy.
std::shared_ptr<const Model> apply_material_overrides(JsonFields& o, std::shared_ptr<const Model> shared) {
    if (!o.has("reflectance") && !o.has("materials") && !o.has("medium")) return shared;
    auto model = std::make_shared<Model>(*shared);
    if (o.has("medium")) {
        JsonFields medium(o.object("medium"), o.file(), o.path_of("medium"));
        Material m;
        if (medium.has("mor_m")) {
            if (medium.has("extinction_per_km")) medium.fail("mor_m", "give mor_m or extinction_per_km, not both");
            m = fog_medium("", medium.number("mor_m", 1.0, 1e6));
        } else {
            m.extinction_per_m = medium.number("extinction_per_km", 1e-6, 1e6) / 1000.0;
            m.backscatter_per_m_sr = medium.number("backscatter_per_km_sr", 0.0, 1e6) / 1000.0;
        }
        medium.reject_unknown_keys();
        for (auto& material : model->materials) {
            material.extinction_per_m = m.extinction_per_m;
            material.backscatter_per_m_sr = m.backscatter_per_m_sr;
        }
    }
    if (o.has("reflectance")) {
        const double rho = o.number("reflectance", 0.0, 1.0);
        for (auto& m : model->materials) m.reflectance = rho;
    }
    if (o.has("materials")) {
        const nlohmann::json& overrides = o.object("materials");
        JsonFields materials(overrides, o.file(), o.path_of("materials"));
        for (const auto& item : overrides.items()) {
            const std::string& name = item.key();
            const auto named = [&](const Material& m) { return m.name == name; };
            if (std::none_of(model->materials.begin(), model->materials.end(), named)) {
                std::string names;
                for (const auto& m : model->materials) names += (names.empty() ? "\"" : ", \"") + m.name + "\"";
                materials.fail(name, "no material of this name in " + model->source + " (it has: " + names + ")");
            }
            JsonFields override_fields(materials.object(name), o.file(), materials.path_of(name));
            const double rho = override_fields.number("reflectance", 0.0, 1.0);
            override_fields.reject_unknown_keys();
            for (auto& m : model->materials) {
                if (named(m)) m.reflectance = rho;
            }
        }
    }
    return model;
}

/// `animation`: "all" (the default: every animation of the model, looping from time 0), "none",
/// or the name of one of the model's glTF animations.
AnimationChoice read_animation_choice(JsonFields& o, const Model& model) {
    AnimationChoice choice;
    const std::string name = o.string("animation", "all");
    if (name == "all") return choice;
    if (name == "none") {
        choice.mode = AnimationChoice::Mode::none;
        return choice;
    }
    std::string names;
    if (model.animation) {
        const auto& clips = model.animation->clips;
        for (std::size_t c = 0; c < clips.size(); ++c) {
            if (clips[c].name == name) {
                choice.mode = AnimationChoice::Mode::one;
                choice.clip = static_cast<std::uint32_t>(c);
                return choice;
            }
            names += (names.empty() ? "\"" : ", \"") + clips[c].name + "\"";
        }
    }
    o.fail("animation", "no animation of this name in " + model.source + " (give \"all\", \"none\"" +
                            (names.empty() ? std::string(": it has none)") : " or one of: " + names + ")"));
}

SceneObject read_object(JsonFields& o, std::uint32_t id, const fs::path& scenario_dir, ModelCache& models) {
    SceneObject object;
    object.id = id;
    object.object_class = *object_class_from_string(required_choice(o, "class", object_class_names()));
    object.name = o.string("name", std::string(to_string(object.object_class)) + "-" + std::to_string(object.id));

    const fs::path model_file = scenario_dir / o.string("model");
    if (!fs::is_regular_file(model_file)) o.fail("model", "no such file: " + model_file.string());
    std::shared_ptr<const Model> model;
    // A broken model file is named with the field that led to it.
    try {
        model = models.get(model_file);
    } catch (const InputError& e) {
        o.fail("model", e.what());
    }
    object.model = apply_material_overrides(o, model);
    object.animation = read_animation_choice(o, *object.model);

    if (o.has("size_m") && o.has("scale")) o.fail("scale", "give size_m or scale, not both");
    if (o.has("size_m")) {
        const double size_m = positive(o, "size_m", kMaxDistance_m);
        const double extent = object.model->bounds().sizes().maxCoeff();
        if (!(extent > 0.0)) o.fail("size_m", object.model->source + " has no extent to scale");
        object.scale = size_m / extent;
    } else {
        object.scale = positive(o, "scale", kMaxScale, 1.0);
    }

    JsonFields trajectory(o.object("trajectory"), o.file(), o.path_of("trajectory"));
    object.trajectory = read_trajectory(trajectory);
    o.reject_unknown_keys();
    return object;
}

BackgroundMap read_background(JsonFields& b, const fs::path& scenario_dir) {
    const fs::path file = scenario_dir / b.string("file");
    if (!fs::is_regular_file(file)) b.fail("file", "no such file: " + file.string());
    BackgroundOptions options;
    options.scale = b.number("scale", 1e-6, 1e6, 1.0);
    options.offset_m = b.vec3("offset_m", Eigen::Vector3d::Zero());
    options.heading_deg = b.number("heading_deg", -360.0, 360.0, 0.0);
    options.normal_neighbours = static_cast<int>(b.integer("neighbours", 3, 64, options.normal_neighbours));
    if (b.has("scanner_position_m")) options.scanner_position_m = b.vec3("scanner_position_m");
    const int reflectance_keys = b.has("reflectance") + b.has("reflectance_at_max_intensity") + b.has("reflectance_per_intensity");
    if (reflectance_keys > 1) {
        b.fail(b.has("reflectance_per_intensity") ? "reflectance_per_intensity" : "reflectance_at_max_intensity",
               "give one of reflectance (one value for every point), reflectance_at_max_intensity or "
               "reflectance_per_intensity (both from the file's intensity)");
    }
    if (b.has("reflectance")) options.reflectance = b.number("reflectance", 0.0, 1.0);
    options.reflectance_at_max_intensity =
        b.number("reflectance_at_max_intensity", 0.0, 1.0, options.reflectance_at_max_intensity);
    if (b.has("reflectance_per_intensity"))
        options.reflectance_per_intensity = b.number("reflectance_per_intensity", 0.0, 1.0);
    b.reject_unknown_keys();
    try {
        return load_background_map(file, options);
    } catch (const InputError& e) {
        b.fail("file", e.what());  // a broken map is named with the field that led to it
    }
}

}  // namespace

Scene read_scene(JsonFields& scenario, const std::filesystem::path& scenario_dir) {
    Scene scene;
    if (scenario.has("objects")) {
        const nlohmann::json& objects = scenario.array("objects");
        const std::string objects_path = scenario.path_of("objects");
        ModelCache models;
        std::map<std::uint32_t, std::size_t> index_of_id;
        for (std::size_t i = 0; i < objects.size(); ++i) {
            JsonFields o(objects[i], scenario.file(), index_path(objects_path, i));
            const auto id = static_cast<std::uint32_t>(o.integer("id", 1, 0xFFFFFFFDLL));
            if (const auto [first, inserted] = index_of_id.emplace(id, i); !inserted) {
                o.fail("id", std::to_string(id) + " is already the id of " + index_path(objects_path, first->second));
            }
            scene.objects.push_back(read_object(o, id, scenario_dir, models));
        }
    }
    if (scenario.has("background")) {
        JsonFields background(scenario.object("background"), scenario.file(), scenario.path_of("background"));
        scene.background = read_background(background, scenario_dir);
    }
    return scene;
}

}  // namespace ladarsim::scene
