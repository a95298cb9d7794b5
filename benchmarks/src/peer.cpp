#include "peer.h"

#include <cmath>
#include <memory>
#include <numbers>

#include "bench_frames.h"
#include "ladarsim/scene/procedural_models.h"
#include "ladarsim/core/units.h"

namespace ladarsim::bench {

namespace {

scene::SceneObject fixed_object(std::uint32_t id, scene::ObjectClass c, scene::Model model, const scene::Pose& pose) {
    scene::SceneObject o;
    o.id = id;
    o.object_class = c;
    o.name = c == scene::ObjectClass::terrain ? "plane" : "sphere";
    o.model = std::make_shared<const scene::Model>(std::move(model));
    o.trajectory = scene::Trajectory::fixed(pose);
    return o;
}

}  // namespace

nlohmann::json peer_scene(const sensor_model::Scenario& base, const BenchOptions& options) {
    // The sensor 2 m up; a 1 m sphere (reflectance 0.5) resting on a flat 1 km ground plane
    // (0.3) 200 m ahead. The 0.5 deg field spans 1.75 m there: half of it on the sphere, the rest
    // on the plane behind it at grazing incidence, out to the sky.
    sensor_model::Scenario s = base;
    s.scene.objects.clear();
    s.scene.background.reset();
    s.mount.position_world = Eigen::Vector3d(0.0, 0.0, 2.0);
    s.mount.orientation = Eigen::Quaterniond::Identity();
    s.mount.cue_object_id = 0;
    const Eigen::Vector3d sphere_centre(200.0, 0.0, 0.5);
    s.mount.gimbal_az_deg = 0.0;
    s.mount.gimbal_el_deg = std::atan2(sphere_centre.z() - 2.0, sphere_centre.x()) / kDeg;
    // The plate faces +-x; pitched by 90 degrees it lies flat.
    const Eigen::Quaterniond flat(Eigen::AngleAxisd(0.5 * std::numbers::pi, Eigen::Vector3d::UnitY()));
    s.scene.objects.push_back(fixed_object(1, scene::ObjectClass::terrain, scene::make_plate(1000.0, 0.3),
                                           scene::Pose{Eigen::Vector3d(500.0, 0.0, 0.0), flat}));
    s.scene.objects.push_back(fixed_object(2, scene::ObjectClass::building, scene::make_sphere(1.0, 0.5),
                                           scene::Pose{sphere_centre, Eigen::Quaterniond::Identity()}));
    const int frames = options.quick ? 10 : 40;
    std::vector<std::uint64_t> indices;
    for (int i = 0; i < frames; ++i) indices.push_back(static_cast<std::uint64_t>(i));
    nlohmann::json settings = nlohmann::json::array();
    for (const int samples : {19, 0}) {
        options.progress(std::string("plane and sphere: ") + (samples ? "19 sub-rays" : "adaptive"));
        const Rendering r = render_frames(with_footprint(s, samples, s.render.footprint_tolerance), indices);
        std::uint64_t returns = 0;
        for (const Frame& f : r.frames) returns += f.returns.size();
        settings.push_back({{"footprint_samples", samples},
                            {"footprint_tolerance", samples ? 0.0 : s.render.footprint_tolerance},
                            {"pulses_per_s", r.beams_per_second()},
                            {"rays_per_pulse", r.rays_per_beam()},
                            {"returns_per_pulse", double(returns) / double(r.beams)}});
    }
    return {{"scene", "1 m sphere 200 m ahead on a flat plane, sensor 2 m up, aimed at the sphere"},
            {"pulse_width_ns", s.sensor.transmitter.pulse_width_ns},
            {"frames", frames},
            {"pulses_per_frame", s.sensor.scan->beam_count()},
            {"settings", settings}};
}

}  // namespace ladarsim::bench
