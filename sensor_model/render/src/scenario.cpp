#include "ladarsim/sensor_model/render/scenario.h"

#include <limits>

#include "ladarsim/core/input_error.h"
#include "ladarsim/core/json_fields.h"
#include "ladarsim/scene/scene_file.h"
#include "ladarsim/scene/trajectory.h"
#include "ladarsim/sensor_model/render/render_dataset.h"
#include "scenario_document.h"

namespace ladarsim::sensor_model {

Eigen::Isometry3d SensorMount::world_from_sensor() const {
    return scene::Pose{position_world, orientation}.world_from_object();
}

namespace {

SensorMount read_mount(JsonFields& sensor) {
    SensorMount m;
    m.position_world = sensor.vec3("position_m");
    m.orientation = scene::orientation_from_ypr_deg(sensor.number("yaw_deg", -360.0, 360.0, 0.0),
                                                    sensor.number("pitch_deg", -90.0, 90.0, 0.0),
                                                    sensor.number("roll_deg", -180.0, 180.0, 0.0));
    if (sensor.has("gimbal_az_deg")) m.gimbal_az_deg = sensor.number("gimbal_az_deg", -180.0, 180.0);
    if (sensor.has("gimbal_el_deg")) m.gimbal_el_deg = sensor.number("gimbal_el_deg", -90.0, 90.0);
    m.cue_object_id = static_cast<std::uint32_t>(sensor.integer("cue_object", 0, 0xFFFFFFFFLL, 0));
    return m;
}

RenderSettings read_render(JsonFields& render) {
    RenderSettings r;
    r.frames = static_cast<int>(render.integer("frames", 1, kMaxFrames, r.frames));
    r.seed = static_cast<std::uint64_t>(render.integer("seed", 0, std::numeric_limits<long long>::max(), 1));
    r.start_time_s = render.number("start_time_s", -1e9, 1e9, r.start_time_s);
    r.motion_steps = static_cast<int>(render.integer("motion_steps", 2, 129, r.motion_steps));
    r.jitter = render.boolean("jitter", r.jitter);
    r.noise = render.boolean("noise", r.noise);
    r.footprint_samples = static_cast<int>(render.integer("footprint_samples", 0, 4096, r.footprint_samples));
    r.footprint_tolerance = render.number("footprint_tolerance", 1e-4, 1.0, r.footprint_tolerance);
    r.footprint_truncation = render.number("footprint_truncation", 0.1, 4.0, r.footprint_truncation);
    r.waveforms = render.boolean("waveforms", r.waveforms);
    render.reject_unknown_keys();
    return r;
}

}  // namespace

namespace {

/// The scenario of `source` (its `extends` already applied), which goes by the name `file`.
Scenario read_scenario(nlohmann::json source, const std::filesystem::path& file) {
    const std::string name = file.string();
    Scenario s;
    s.file = file;
    s.source = std::move(source);

    JsonFields top(s.source, name, "");
    {
        JsonFields sensor(top.object("sensor"), name, "sensor");
        s.sensor = read_scenario_sensor(sensor, file.parent_path());
        s.mount = read_mount(sensor);
        sensor.reject_unknown_keys();
    }
    if (top.has("render")) {
        JsonFields render(top.object("render"), name, "render");
        s.render = read_render(render);
    }
    if (top.has("atmosphere")) {
        JsonFields atmosphere(top.object("atmosphere"), name, "atmosphere");
        s.atmosphere = read_atmosphere(atmosphere);
    }
    s.scene = scene::read_scene(top, file.parent_path());
    top.reject_unknown_keys();

    if (s.mount.cue_object_id != 0) {
        bool found = false;
        for (const auto& o : s.scene.objects) found = found || o.id == s.mount.cue_object_id;
        if (!found) throw InputError(name, "sensor.cue_object", "no object has id " + std::to_string(s.mount.cue_object_id));
    }
    return s;
}

}  // namespace

Scenario load_scenario(const std::filesystem::path& file) { return read_scenario(read_scenario_document(file), file); }

Scenario load_scenario(const nlohmann::json& document, const std::filesystem::path& base_dir) {
    const std::filesystem::path file = base_dir / kInMemoryScenarioName;
    return read_scenario(extend_scenario_document(document, file), file);
}

}  // namespace ladarsim::sensor_model
