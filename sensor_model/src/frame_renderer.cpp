#include "ladarsim/sensor_model/frame_renderer.h"

#include <algorithm>
#include <map>
#include <numbers>

#include <tbb/parallel_for.h>

#include "ladarsim/sensor_model/beam_geometry.h"
#include "ladarsim/sensor_model/counter_random.h"
#include "ladarsim/sensor_model/physical_constants.h"
#include "ladarsim/sensor_model/range_equation.h"
#include "ladarsim/sensor_model/volume_echoes.h"

namespace ladarsim::sensor_model {

namespace {

constexpr double kMradToRad = 1e-3;

GimbalPointing initial_pointing(const SensorMount& mount, GimbalPointing cue, bool has_cue) {
    constexpr double kRad = std::numbers::pi / 180.0;
    GimbalPointing p = has_cue ? cue : GimbalPointing{};
    if (mount.gimbal_az_deg) p.az_rad = *mount.gimbal_az_deg * kRad;
    if (mount.gimbal_el_deg) p.el_rad = *mount.gimbal_el_deg * kRad;
    return p;
}

struct SubRayHit {
    double range_m;
    double weight;
    double energy_j;  ///< reaching the detector, by the range equation
    std::uint32_t object_id;
    Eigen::Vector3d point_world;
    Eigen::Vector3f normal_world;
};

/// Two sub-ray hits (sorted by range) belong to one surface when their ranges are within the gap,
/// or when they lie on one object's locally continuous surface: each within the gap of the other's
/// tangent plane. Without the second rule a surface seen at grazing incidence, whose footprint
/// spans metres in range, would break into one return per sub-ray.
bool same_surface(const SubRayHit& a, const SubRayHit& b, double gap_m) {
    if (b.range_m - a.range_m <= gap_m) return true;
    if (a.object_id != b.object_id) return false;
    const Eigen::Vector3d d = b.point_world - a.point_world;
    return std::abs(a.normal_world.cast<double>().dot(d)) <= gap_m && std::abs(b.normal_world.cast<double>().dot(d)) <= gap_m;
}

}  // namespace

Eigen::Vector3d object_centre_world(const scene::SceneObject& object, double time_s) {
    const Eigen::Vector3d centre_model = object.scale * object.model->bounds().center().cast<double>();
    return object.trajectory.at(time_s).world_from_object() * centre_model;
}

FrameRenderer::FrameRenderer(const Scenario& scenario)
    : scenario_(scenario),
      traced_(scenario.scene, scenario.mount.position_world),
      raster_(scenario.sensor),
      footprint_(scenario.sensor.divergence_mrad * kMradToRad, scenario.sensor.footprint_samples,
                 scenario.sensor.footprint_truncation),
      receiver_(scenario.sensor, scenario.atmosphere, scenario.render.noise) {}

double FrameRenderer::frame_start_s(std::uint64_t index) const {
    return scenario_.render.start_time_s + static_cast<double>(index) / scenario_.sensor.frame_rate_hz;
}

GimbalPointing FrameRenderer::cue_pointing(double time_s) const {
    for (const auto& object : scenario_.scene.objects) {
        if (object.id != scenario_.mount.cue_object_id) continue;
        const Eigen::Vector3d in_sensor =
            scenario_.mount.world_from_sensor().inverse() * object_centre_world(object, time_s);
        return pointing_towards(in_sensor);
    }
    return {};
}

GimbalPointing FrameRenderer::gimbal_pointing(std::uint64_t index) {
    const bool cued = scenario_.mount.cue_object_id != 0;
    if (pointing_by_frame_.empty()) {
        Gimbal g(scenario_.sensor, initial_pointing(scenario_.mount, cue_pointing(frame_start_s(0)), cued));
        pointing_by_frame_.push_back(g.pointing());
    }
    // The gimbal moves between frames, so frame k's pointing depends on every earlier frame:
    // replay from the last known frame (cheap: two angles per frame).
    while (pointing_by_frame_.size() <= index) {
        const std::uint64_t next = pointing_by_frame_.size();
        Gimbal g(scenario_.sensor, pointing_by_frame_.back());
        if (cued) g.slew_towards(cue_pointing(frame_start_s(next)), 1.0 / scenario_.sensor.frame_rate_hz);
        pointing_by_frame_.push_back(g.pointing());
    }
    return pointing_by_frame_[index];
}

std::vector<Return> FrameRenderer::trace_row(int row, GimbalPointing pointing, double frame_start_s,
                                             std::uint64_t frame) const {
    const auto& sensor = scenario_.sensor;
    const Eigen::Isometry3d world_from_sensor = scenario_.mount.world_from_sensor();
    const int samples = footprint_.samples();
    // The footprint is round in units of the azimuth divergence; elliptical beams stretch it in elevation.
    const double ellipticity = sensor.divergence_el_mrad / sensor.divergence_mrad;
    std::vector<SubRay> sub_rays(static_cast<std::size_t>(samples));
    std::vector<double> uniforms(2 * static_cast<std::size_t>(samples));
    std::vector<raytrace::Ray> rays(static_cast<std::size_t>(samples));
    std::vector<std::optional<raytrace::Hit>> hits(static_cast<std::size_t>(samples));
    std::vector<SubRayHit> surface_hits;
    surface_hits.reserve(static_cast<std::size_t>(samples));
    std::vector<Return> returns;
    const double pulse_energy_j = sensor.pulse_energy_j();
    const double aperture_area_m2 = sensor.aperture_area_m2();
    // Primary photo-electrons per joule on the detector: responsivity / q.
    const double photoelectrons_per_joule = sensor.responsivity_a_per_w / kElementaryCharge_c;

    for (int step = 0; step < raster_.columns(); ++step) {
        const int cell_index = row * raster_.columns() + step;  // keys the beam's random draws
        const RasterBeam beam = raster_.beam(row, step);
        const Eigen::Matrix3d sensor_from_beam_m = sensor_from_beam(pointing, beam.az_offset_rad, beam.el_offset_rad);
        const Eigen::Matrix3d world_from_beam = world_from_sensor.linear() * sensor_from_beam_m;
        const double time_s = frame_start_s + beam.time_offset_s;

        if (scenario_.render.jitter) {
            for (int i = 0; i < samples; ++i) {
                const auto u = uniform4(scenario_.render.seed, RandomStream::footprint_jitter, frame,
                                        static_cast<std::uint32_t>(cell_index), static_cast<std::uint32_t>(i));
                uniforms[2 * i] = u[0];
                uniforms[2 * i + 1] = u[1];
            }
            footprint_.jittered(sub_rays, uniforms);
        } else {
            footprint_.fixed(sub_rays);
        }
        for (int i = 0; i < samples; ++i) {
            const Eigen::Vector3d in_beam(1.0, std::tan(sub_rays[i].offset_x_rad),
                                          std::tan(sub_rays[i].offset_y_rad * ellipticity));
            rays[i].origin_world = scenario_.mount.position_world;
            rays[i].direction = (world_from_beam * in_beam).normalized();
            rays[i].time_s = time_s;
            rays[i].max_range_m = sensor.max_range_m;
        }
        traced_.trace(rays, hits);

        surface_hits.clear();
        std::vector<BeamSurface> volume_surfaces;
        RandomSequence volume_draws(scenario_.render.seed, RandomStream::volume_scatter, frame,
                                    static_cast<std::uint32_t>(cell_index));
        for (int i = 0; i < samples; ++i) {
            std::vector<raytrace::VolumeSegment> volumes;
            if (traced_.has_volumes()) {
                volumes = traced_.volumes_along(rays[i]);
                add_volume_echoes(volumes, hits[i] ? hits[i]->range_m : sensor.max_range_m,
                                  pulse_energy_j * sub_rays[i].weight * sensor.optics_efficiency, sub_rays[i].weight,
                                  aperture_area_m2, receiver_, volume_draws, volume_surfaces);
            }
            if (!hits[i]) continue;
            const auto& h = *hits[i];
            const double t = receiver_.transmission(h.range_m);
            const double fog = std::exp(-2.0 * optical_depth(volumes, h.range_m));
            const double energy = lambertian_echo_energy_j(pulse_energy_j, sub_rays[i].weight, sensor.optics_efficiency,
                                                           t * t * fog, h.reflectance, h.cos_incidence, aperture_area_m2,
                                                           h.range_m);
            surface_hits.push_back({h.range_m, sub_rays[i].weight, energy, h.object_id,
                                    rays[i].origin_world + h.range_m * rays[i].direction, h.normal_world});
        }
        std::sort(surface_hits.begin(), surface_hits.end(),
                  [](const SubRayHit& a, const SubRayHit& b) { return a.range_m < b.range_m; });

        // One BeamSurface per run of hits on one surface, named after the object carrying most
        // of its energy.
        std::vector<BeamSurface> surfaces;
        for (std::size_t first = 0; first < surface_hits.size();) {
            std::size_t last = first + 1;
            while (last < surface_hits.size() && same_surface(surface_hits[last - 1], surface_hits[last], sensor.return_gap_m)) {
                ++last;
            }
            BeamSurface surface;
            bool one_object = true;
            for (std::size_t k = first; k < last; ++k) {
                surface.weight += surface_hits[k].weight;
                surface.echoes.push_back({surface_hits[k].range_m, surface_hits[k].energy_j, 0});
                one_object = one_object && surface_hits[k].object_id == surface_hits[first].object_id;
            }
            surface.object_id = surface_hits[first].object_id;
            if (!one_object) {  // rare (objects within return_gap_m of each other): tally per object
                std::map<std::uint32_t, double> energy_by_object;
                for (std::size_t k = first; k < last; ++k) energy_by_object[surface_hits[k].object_id] += surface_hits[k].energy_j;
                surface.object_id = std::max_element(energy_by_object.begin(), energy_by_object.end(),
                                                      [](const auto& a, const auto& b) { return a.second < b.second; })
                                        ->first;
            }
            surfaces.push_back(std::move(surface));
            first = last;
        }

        for (BeamSurface& v : volume_surfaces) surfaces.push_back(std::move(v));

        const Eigen::Vector3d axis_sensor = sensor_from_beam_m.col(0);
        const GimbalPointing beam_angles = pointing_towards(axis_sensor);
        const BeamKey key{scenario_.render.seed, frame, static_cast<std::uint32_t>(cell_index)};
        std::uint8_t return_index = 0;
        for (const DetectedReturn& d : receiver_.receive(std::move(surfaces), key)) {
            Return r;
            r.range_m = d.range_m;
            r.position_sensor = (axis_sensor * r.range_m).cast<float>();
            r.intensity = static_cast<float>(d.energy_j * photoelectrons_per_joule);
            r.snr = static_cast<float>(d.snr);
            r.time_s = time_s;
            r.beam_az_rad = static_cast<float>(beam_angles.az_rad);
            r.beam_el_rad = static_cast<float>(beam_angles.el_rad);
            r.column = static_cast<std::uint16_t>(beam.column);
            r.row = static_cast<std::uint16_t>(beam.row);
            r.return_index = return_index++;
            r.object_id = d.object_id;
            r.source = d.source;
            r.pulse_offset = d.pulse_offset;
            returns.push_back(r);
        }
    }
    // A triangle sweep fires odd lines right to left; frames list returns by column.
    std::stable_sort(returns.begin(), returns.end(),
                     [](const Return& a, const Return& b) { return a.column < b.column; });
    return returns;
}

std::vector<GroundTruthObject> FrameRenderer::ground_truth(double time_s, const std::vector<Return>& returns) const {
    const Eigen::Isometry3d sensor_from_world = scenario_.mount.world_from_sensor().inverse();
    const Eigen::Quaterniond sensor_from_world_rotation(sensor_from_world.linear());
    std::vector<GroundTruthObject> truth;
    for (const auto& object : scenario_.scene.objects) {
        const scene::Pose pose = object.trajectory.at(time_s);
        GroundTruthObject g;
        g.object_id = object.id;
        g.object_class = std::string(scene::to_string(object.object_class));
        g.name = object.name;
        g.time_s = time_s;
        g.box_world.centre = object_centre_world(object, time_s);
        g.box_world.size = object.scale * object.model->bounds().sizes().cast<double>();
        g.box_world.orientation = pose.orientation.normalized();
        g.box_sensor.centre = sensor_from_world * g.box_world.centre;
        g.box_sensor.size = g.box_world.size;
        g.box_sensor.orientation = (sensor_from_world_rotation * g.box_world.orientation).normalized();
        for (const Return& r : returns) {
            if (r.object_id != object.id) continue;
            ++g.returns;
            if (r.pulse_offset > 0) ++g.folded_returns;
        }
        truth.push_back(std::move(g));
    }
    return truth;
}

Frame FrameRenderer::render(std::uint64_t index) { return render_at(index, gimbal_pointing(index)); }

Frame FrameRenderer::render_at(std::uint64_t index, GimbalPointing pointing) {
    Frame frame;
    frame.index = index;
    frame.start_time_s = frame_start_s(index);
    frame.end_time_s = frame.start_time_s + scenario_.sensor.frame_scan_duration_s();
    frame.columns = raster_.columns();
    frame.rows = raster_.rows();
    frame.gimbal_az_rad = pointing.az_rad;
    frame.gimbal_el_rad = pointing.el_rad;

    traced_.set_time_window(frame.start_time_s, frame.end_time_s, scenario_.render.motion_steps);

    std::vector<std::vector<Return>> by_row(static_cast<std::size_t>(raster_.rows()));
    tbb::parallel_for(0, raster_.rows(), [&](int row) {
        by_row[static_cast<std::size_t>(row)] = trace_row(row, pointing, frame.start_time_s, index);
    });
    std::size_t total = 0;
    for (const auto& r : by_row) total += r.size();
    frame.returns.reserve(total);
    for (auto& r : by_row) frame.returns.insert(frame.returns.end(), r.begin(), r.end());

    frame.ground_truth = ground_truth(0.5 * (frame.start_time_s + frame.end_time_s), frame.returns);
    return frame;
}

}  // namespace ladarsim::sensor_model
