#include "ladarsim/sensor_model/render/frame_renderer.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

#include <tbb/parallel_for.h>

#include "ladarsim/scene/animation.h"
#include "ladarsim/scene/scene.h"
#include "ladarsim/sensor_model/sensor/beam_geometry.h"
#include "ladarsim/sensor_model/signal/counter_random.h"
#include "ladarsim/sensor_model/sensor/physical_constants.h"
#include "ladarsim/core/units.h"

namespace ladarsim::sensor_model {

namespace {

GimbalPointing initial_pointing(const SensorMount& mount, GimbalPointing cue, bool has_cue) {
    GimbalPointing p = has_cue ? cue : GimbalPointing{};
    if (mount.gimbal_az_deg) p.az_rad = *mount.gimbal_az_deg * kDeg;
    if (mount.gimbal_el_deg) p.el_rad = *mount.gimbal_el_deg * kDeg;
    return p;
}

/// A frame's waveform record before its windows: the receiver constants its samples are read with.
FrameWaveforms waveform_header(std::uint64_t frame, const Scenario& scenario, const BeamReceiver& receiver) {
    FrameWaveforms w;
    w.frame = frame;
    const ApdReceiver& apd = receiver.apd();
    w.receiver.sample_interval_s = receiver.waveform().bin_s();
    w.receiver.pulse_fwhm_s = scenario.sensor.transmitter.pulse_width_ns * 1e-9;
    w.receiver.threshold_a = apd.threshold_a();
    w.receiver.release_a = receiver.waveform().release_a();
    w.receiver.noise_floor_a = apd.noise_floor_a();
    w.receiver.saturation_a = apd.saturation_a();
    // Frames report intensity as primary photo-electrons per joule on the detector (responsivity / q).
    w.receiver.photoelectrons_per_coulomb = scenario.sensor.receiver.responsivity_a_per_w / kElementaryCharge_c / apd.amps_per_watt();
    return w;
}

/// What the footprint integrator takes of the scenario.
FootprintSettings footprint_settings(const Scenario& scenario) {
    FootprintSettings settings;
    settings.origin_world = scenario.mount.position_world;
    settings.samples = scenario.render.footprint_samples;
    settings.map_lines = scenario.render.footprint_map_lines;
    settings.tolerance = scenario.render.footprint_tolerance;
    settings.truncation = scenario.render.footprint_truncation;
    settings.jitter = scenario.render.jitter;
    settings.seed = scenario.render.seed;
    return settings;
}

}  // namespace

Eigen::Vector3d object_centre_world(const scene::SceneObject& object, double time_s) {
    const Eigen::Vector3d centre_model = object.scale * object.model->bounds().center().cast<double>();
    return object.trajectory.at(time_s).world_from_object() * centre_model;
}

FrameRenderer::FrameRenderer(const Scenario& scenario)
    : scenario_(scenario),
      traced_(scenario.scene, scenario.mount.position_world),
      raster_(*scenario.sensor.scan),
      receiver_(scenario.sensor, scenario.atmosphere, scenario.render.noise),
      radiometry_(scenario.sensor, receiver_),
      integrator_(footprint_settings(scenario), scenario.sensor, scenario.scene.objects,
                  scenario.scene.background ? &*scenario.scene.background : nullptr, traced_, radiometry_),
      world_from_sensor_rotation_(scenario.mount.world_from_sensor().linear()) {
    using Eigen::AngleAxisd;
    for (int row = 0; row < raster_.rows(); ++row) {
        for (int step = 0; step < raster_.columns(); ++step) {
            const RasterBeam beam = raster_.beam(row, step);
            offset_rotations_.push_back({Eigen::Quaterniond(AngleAxisd(beam.az_offset_rad, Eigen::Vector3d::UnitZ())),
                                         Eigen::Quaterniond(AngleAxisd(-beam.el_offset_rad, Eigen::Vector3d::UnitY()))});
        }
    }
    for (const auto& object : scenario.scene.objects)
        truth_boxes_model_.push_back(scene::animates(*object.model, object.animation) ? scene::animated_bounds(*object.model, object.animation)
                                                                                      : Eigen::AlignedBox3d());
    if (integrator_.adaptive()) find_neighbours();
    // Shared map lines and the target lattice both trace from one place for a whole row: not from
    // a moving platform (each beam then integrates from its own origin).
    if (!scenario.mount.moves()) integrator_.share_map_rows(raster_);
    if (integrator_.adaptive() && !scenario.mount.moves() && TargetLattice::worthwhile(integrator_.shape().footprint(), raster_)) {
        target_lattice_ = std::make_unique<TargetLattice>(traced_, raster_, integrator_.shape(), radiometry_, integrator_.grid_base(),
                                                          scenario.mount.position_world,
                                                          world_from_sensor_rotation_, scenario.sensor.receiver.max_range_m,
                                                          scenario.render.seed, scenario.render.jitter);
        integrator_.share_target_sub_rays(target_lattice_.get());
    }
}

namespace {

/// Probes (neighbours' axes) inside a footprint per footprint radius along each axis, at most.
/// The default scenario with 8: 690 k beams/s on one thread; with 4: 13 % faster, the bench's
/// accuracy tables unchanged but for a tenth of a percent here and there.
constexpr int kProbesPerRadius = 4;

}  // namespace

void FrameRenderer::find_neighbours() {
    const double ellipticity = integrator_.shape().ellipticity();
    const double column_pitch = raster_.pitch_az_rad();
    const double row_pitch = raster_.pitch_el_rad();
    const double r_max = integrator_.shape().footprint().max_offset_rad();
    // Neighbours whose axes fall inside the footprint (in footprint coordinates, elevation
    // divided by the ellipticity), thinned to about 8 per footprint radius and axis: a denser
    // raster adds cost, not information.
    const int reach_columns = std::min(static_cast<int>(r_max / column_pitch), raster_.columns());
    const int reach_rows = std::min(static_cast<int>(r_max * ellipticity / row_pitch), raster_.rows());
    const int stride_columns = std::max(1, (reach_columns + 7) / 8);
    const int stride_rows = std::max(1, (reach_rows + 7) / 8);
    // Beyond the footprint, a ring of sentinels one (thinned) pitch of the denser axis wide:
    // something they meet may reach into the footprint's rim where no probe inside does.
    const double sentinel_reach = r_max + std::min(stride_columns * column_pitch, stride_rows * row_pitch / ellipticity);
    const int sentinel_columns = std::min(static_cast<int>(sentinel_reach / column_pitch), raster_.columns());
    const int sentinel_rows = std::min(static_cast<int>(sentinel_reach * ellipticity / row_pitch), raster_.rows());
    for (int dr = -sentinel_rows / stride_rows * stride_rows; dr <= sentinel_rows; dr += stride_rows) {
        for (int dc = -sentinel_columns / stride_columns * stride_columns; dc <= sentinel_columns; dc += stride_columns) {
            if (dr == 0 && dc == 0) continue;
            // Columns count to the right and rows down; offsets are positive left and up.
            const double x = -dc * column_pitch, y = -dr * row_pitch / ellipticity;
            if (x * x + y * y <= sentinel_reach * sentinel_reach)
                neighbours_.push_back({dr, dc, x, y, integrator_.shape().irradiance(x, y), x * x + y * y <= r_max * r_max});
        }
    }
    // Inside the footprint, where that keeps every axis, the probes are thinned further, to about
    // kProbesPerRadius: on a grid of the raster's own (every other column of the paper's), so that
    // a beam beside the raster's border keeps the probes its neighbour would (a corner's sliver at
    // its rim showed to the border column's axis, not to a grid counted from the beam), and the
    // border lines and columns themselves. Sentinels stay dense.
    const int probe_columns = stride_columns == 1 ? std::max(1, (reach_columns + kProbesPerRadius - 1) / kProbesPerRadius) : 1;
    const int probe_rows = stride_rows == 1 ? std::max(1, (reach_rows + kProbesPerRadius - 1) / kProbesPerRadius) : 1;
    probe_axis_.assign(static_cast<std::size_t>(raster_.beam_count()), 0);
    for (int row = 0; row < raster_.rows(); ++row)
        for (int column = 0; column < raster_.columns(); ++column)
            probe_axis_[static_cast<std::size_t>(row * raster_.columns() + column)] =
                (row % probe_rows == 0 || row == raster_.rows() - 1) && (column % probe_columns == 0 || column == raster_.columns() - 1);
    // Where no neighbour reaches half-way to the footprint's edge in some direction (the raster's
    // border, or a raster sparser than its footprints), an extra probe at 3/4 of the way does.
    const double reach = 0.75 * r_max;
    extra_offsets_ = {Eigen::Vector2d(reach, 0.0), Eigen::Vector2d(-reach, 0.0), Eigen::Vector2d(0.0, reach),
                      Eigen::Vector2d(0.0, -reach)};
    extra_irradiance_ = integrator_.shape().irradiance(reach, 0.0);
    extra_mask_.assign(static_cast<std::size_t>(raster_.beam_count()), 0);
    for (int row = 0; row < raster_.rows(); ++row) {
        for (int column = 0; column < raster_.columns(); ++column) {
            std::uint8_t covered = 0;
            for (const Neighbour& n : neighbours_) {
                const int r = row + n.d_row, c = column + n.d_column;
                if (r < 0 || r >= raster_.rows() || c < 0 || c >= raster_.columns()) continue;
                if (!n.inside || !probe_axis_[static_cast<std::size_t>(r * raster_.columns() + c)]) continue;  // a sentinel, or thinned out
                for (int k = 0; k < 4; ++k)
                    if (Eigen::Vector2d(n.x_rad, n.y_rad).dot(extra_offsets_[k].normalized()) >= 0.5 * r_max)
                        covered |= static_cast<std::uint8_t>(1u << k);
            }
            extra_mask_[static_cast<std::size_t>(row * raster_.columns() + column)] = static_cast<std::uint8_t>(~covered & 0xFu);
        }
    }
}

double FrameRenderer::frame_start_s(std::uint64_t index) const {
    return scenario_.render.start_time_s + static_cast<double>(index) / raster_.frame_rate_hz();
}

GimbalPointing FrameRenderer::cue_pointing(double time_s) const {
    for (const auto& object : scenario_.scene.objects) {
        if (object.id != scenario_.mount.cue_object_id) continue;
        const Eigen::Vector3d in_sensor =
            scenario_.mount.world_from_sensor(time_s).inverse() * object_centre_world(object, time_s);
        return pointing_towards(in_sensor);
    }
    return {};
}

GimbalPointing FrameRenderer::gimbal_pointing(std::uint64_t index) {
    const bool cued = scenario_.mount.cue_object_id != 0;
    if (pointing_by_frame_.empty()) {
        Gimbal g(scenario_.sensor.gimbal, initial_pointing(scenario_.mount, cue_pointing(frame_start_s(0)), cued));
        pointing_by_frame_.push_back(g.pointing());
    }
    // The gimbal moves between frames, so frame k's pointing depends on every earlier frame:
    // replay from the last known frame (cheap: two angles per frame).
    while (pointing_by_frame_.size() <= index) {
        const std::uint64_t next = pointing_by_frame_.size();
        Gimbal g(scenario_.sensor.gimbal, pointing_by_frame_.back());
        if (cued) g.slew_towards(cue_pointing(frame_start_s(next)), 1.0 / raster_.frame_rate_hz());
        pointing_by_frame_.push_back(g.pointing());
    }
    return pointing_by_frame_[index];
}

BeamAim FrameRenderer::aim(const RasterBeam& beam, int step, const Eigen::Quaterniond& gimbal, const Eigen::Matrix3d& world_from_sensor,
                           const Eigen::Vector3d& origin_world, double time_s) const {
    BeamAim a;
    // sensor_from_beam(pointing, az offset, el offset), composed in the same order.
    const auto& offset = offset_rotations_[static_cast<std::size_t>(beam.row * raster_.columns() + step)];
    a.world_from_beam = world_from_sensor * ((gimbal * offset[0]) * offset[1]).toRotationMatrix();
    a.origin_world = origin_world;
    a.time_s = time_s;
    a.cell = static_cast<std::uint32_t>(beam.row * raster_.columns() + step);  // keys the beam's random draws
    return a;
}

Eigen::Vector3d FrameRenderer::stare_point(std::uint64_t index, GimbalPointing pointing) const {
    const double t = frame_start_s(index);
    const Eigen::Isometry3d world_from_sensor = scenario_.mount.world_from_sensor(t);
    double distance = 0.0;
    for (const auto& object : scenario_.scene.objects)
        if (object.id == scenario_.mount.cue_object_id) distance = (object_centre_world(object, t) - world_from_sensor.translation()).norm();
    return world_from_sensor * (distance * direction_towards(pointing));
}

BeamAim FrameRenderer::aim_moving(const RasterBeam& beam, int step, GimbalPointing pointing, double frame_start_s) const {
    const double time_s = frame_start_s + beam.time_offset_s;
    const Eigen::Isometry3d world_from_sensor = scenario_.mount.world_from_sensor(time_s);
    if (stare_point_) {
        // Stabilised: the gimbal turns against the platform's motion to hold its stare point,
        // within its limits and slew rate (from where the frame started it).
        Gimbal g(scenario_.sensor.gimbal, pointing);
        g.slew_towards(pointing_towards(world_from_sensor.inverse() * *stare_point_), time_s - frame_start_s);
        pointing = g.pointing();
    }
    const Eigen::Quaterniond gimbal = Eigen::AngleAxisd(pointing.az_rad, Eigen::Vector3d::UnitZ()) *
                                      Eigen::AngleAxisd(-pointing.el_rad, Eigen::Vector3d::UnitY());
    return aim(beam, step, gimbal, world_from_sensor.linear(), world_from_sensor.translation(), time_s);
}

std::uint64_t FrameRenderer::aim_row(int row, GimbalPointing pointing, double frame_start_s) {
    const Eigen::Quaterniond gimbal = Eigen::AngleAxisd(pointing.az_rad, Eigen::Vector3d::UnitZ()) *
                                      Eigen::AngleAxisd(-pointing.el_rad, Eigen::Vector3d::UnitY());
    const int columns = raster_.columns();
    const bool moving = scenario_.mount.moves();
    for (int step = 0; step < columns; ++step) {
        const RasterBeam beam = raster_.beam(row, step);
        aims_[static_cast<std::size_t>(row * columns + beam.column)] =
            moving ? aim_moving(beam, step, pointing, frame_start_s)
                   : aim(beam, step, gimbal, world_from_sensor_rotation_, scenario_.mount.position_world, frame_start_s + beam.time_offset_s);
    }
    integrator_.start_map_row(row, world_from_sensor_rotation_ * gimbal.toRotationMatrix());
    if (!integrator_.adaptive()) return 0;

    thread_local std::vector<raytrace::Ray> rays;
    thread_local std::vector<std::optional<raytrace::Hit>> hits;
    thread_local std::vector<ProbeHit*> slots;
    rays.clear();
    slots.clear();
    auto add = [&](const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double time_s, ProbeHit* slot) {
        raytrace::Ray r;
        r.origin_world = origin;
        r.direction = direction;
        r.time_s = time_s;
        r.max_range_m = scenario_.sensor.receiver.max_range_m;
        rays.push_back(r);
        slots.push_back(slot);
    };
    // In firing order: neighbouring rays of the stream leave in nearly the same direction.
    for (int step = 0; step < columns; ++step) {
        const std::size_t cell = static_cast<std::size_t>(row * columns + raster_.beam(row, step).column);
        const BeamAim& a = aims_[cell];
        add(a.origin_world, a.world_from_beam.col(0), a.time_s, &axis_hit_[cell]);
        for (int k = 0; k < 4; ++k) {
            if (!(extra_mask_[cell] & (1u << k))) continue;
            extra_direction_[4 * cell + k] = a.world_from_beam * integrator_.shape().in_beam(extra_offsets_[k].x(), extra_offsets_[k].y());
            add(a.origin_world, extra_direction_[4 * cell + k], a.time_s, &extra_hit_[4 * cell + k]);
        }
    }
    hits.resize(rays.size());
    traced_.trace(rays, hits);
    for (std::size_t i = 0; i < rays.size(); ++i) slots[i]->set(hits[i], rays[i].origin_world, rays[i].direction);
    return rays.size();
}

std::vector<Return> FrameRenderer::trace_steps(int row, int first_step, int end_step, std::uint64_t frame,
                                               std::uint64_t& rays, std::vector<WaveformWindow>* windows) const {
    const auto& sensor = scenario_.sensor;
    const Eigen::Matrix3d fixed_sensor_from_world = scenario_.mount.world_from_sensor().linear().transpose();
    // Primary photo-electrons per joule on the detector: responsivity / q.
    const double photoelectrons_per_joule = sensor.receiver.responsivity_a_per_w / kElementaryCharge_c;
    thread_local std::vector<Probe> probes;
    thread_local BeamEchoes echoes;
    thread_local std::vector<BeamSurface> surfaces;
    thread_local std::vector<DetectedReturn> detected;
    std::vector<Return> returns;
    const int rows = raster_.rows(), columns = raster_.columns();  // virtual: asked once, not per probe

    for (int step = first_step; step < end_step; ++step) {
        const RasterBeam beam = raster_.beam(row, step);
        const std::size_t cell = static_cast<std::size_t>(row * columns + beam.column);
        const BeamAim& a = aims_[cell];
        probes.clear();
        if (integrator_.adaptive()) {
            probes.push_back({0.0, 0.0, 1.0, a.world_from_beam.col(0), &axis_hit_[cell]});
            for (const Neighbour& n : neighbours_) {
                const int r = row + n.d_row, c = beam.column + n.d_column;
                if (r < 0 || r >= rows || c < 0 || c >= columns) continue;
                const std::size_t other = static_cast<std::size_t>(r * columns + c);
                if (n.inside && !probe_axis_[other]) continue;
                probes.push_back({n.x_rad, n.y_rad, n.irradiance, aims_[other].world_from_beam.col(0), &axis_hit_[other]});
            }
            for (int k = 0; k < 4; ++k) {
                if (!(extra_mask_[cell] & (1u << k))) continue;
                probes.push_back({extra_offsets_[k].x(), extra_offsets_[k].y(), extra_irradiance_,
                                  extra_direction_[4 * cell + k], &extra_hit_[4 * cell + k]});
            }
        }
        integrator_.integrate(a, probes, frame, echoes);
        rays += static_cast<std::uint64_t>(echoes.rays);
        gather_surfaces(echoes.surface, sensor.receiver.return_gap_m, surfaces);
        for (BeamSurface& s : surfaces) s.profiled = s.object_id == scene::kBackgroundObjectId;
        for (BeamSurface& v : echoes.volume) surfaces.push_back(std::move(v));

        const BeamKey key{scenario_.render.seed, frame, a.cell};
        std::uint8_t return_index = 0;
        const std::size_t windows_before = windows ? windows->size() : 0;
        receiver_.receive(surfaces, key, detected, windows);
        if (windows)
            for (std::size_t w = windows_before; w < windows->size(); ++w) {
                (*windows)[w].column = static_cast<std::uint16_t>(beam.column);
                (*windows)[w].row = static_cast<std::uint16_t>(beam.row);
                (*windows)[w].time_s = a.time_s;
            }
        if (detected.empty()) continue;
        // In the sensor frame at the pulse's time, as a real sensor reports it.
        const Eigen::Matrix3d sensor_from_world = scenario_.mount.moves()
                                                      ? Eigen::Matrix3d(scenario_.mount.world_from_sensor(a.time_s).linear().transpose())
                                                      : fixed_sensor_from_world;
        const Eigen::Vector3d axis_sensor = sensor_from_world * a.world_from_beam.col(0);
        const GimbalPointing beam_angles = pointing_towards(axis_sensor);
        for (const DetectedReturn& d : detected) {
            Return r;
            r.range_m = d.range_m;
            r.position_sensor = (axis_sensor * r.range_m).cast<float>();
            r.intensity = static_cast<float>(d.energy_j * photoelectrons_per_joule);
            r.snr = static_cast<float>(d.snr);
            r.time_s = a.time_s;
            r.beam_az_rad = static_cast<float>(beam_angles.az_rad);
            r.beam_el_rad = static_cast<float>(beam_angles.el_rad);
            r.column = static_cast<std::uint16_t>(beam.column);
            r.row = static_cast<std::uint16_t>(beam.row);
            r.return_index = return_index++;
            r.object_id = d.object_id;
            r.source = d.source;
            r.pulse_offset = d.pulse_offset;
            r.saturated = d.saturated;
            returns.push_back(r);
        }
    }
    return returns;
}

std::vector<GroundTruthObject> FrameRenderer::ground_truth(double time_s, const std::vector<Return>& returns) const {
    const Eigen::Isometry3d sensor_from_world = scenario_.mount.world_from_sensor(time_s).inverse();
    const Eigen::Quaterniond sensor_from_world_rotation(sensor_from_world.linear());
    std::vector<GroundTruthObject> truth;
    for (std::size_t k = 0; k < scenario_.scene.objects.size(); ++k) {
        const scene::SceneObject& object = scenario_.scene.objects[k];
        const scene::Pose pose = object.trajectory.at(time_s);
        const Eigen::AlignedBox3d& animated_box = truth_boxes_model_[k];
        GroundTruthObject g;
        g.object_id = object.id;
        g.object_class = std::string(scene::to_string(object.object_class));
        g.name = object.name;
        g.time_s = time_s;
        if (animated_box.isEmpty()) {
            g.box_world.centre = object_centre_world(object, time_s);
            g.box_world.size = object.scale * object.model->bounds().sizes().cast<double>();
        } else {
            g.box_world.centre = pose.world_from_object() * (object.scale * animated_box.center());
            g.box_world.size = object.scale * animated_box.sizes();
        }
        g.box_world.orientation = pose.orientation.normalized();
        g.box_sensor.centre = sensor_from_world * g.box_world.centre;
        g.box_sensor.size = g.box_world.size;
        g.box_sensor.orientation = (sensor_from_world_rotation * g.box_world.orientation).normalized();
        for (const Return& r : returns) {
            if (r.object_id != object.id) continue;
            ++g.returns;
            if (r.pulse_offset > 0) ++g.folded_returns;
            if (r.saturated) ++g.saturated_returns;
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
    frame.end_time_s = frame.start_time_s + raster_.frame_scan_duration_s();
    frame.columns = raster_.columns();
    frame.rows = raster_.rows();
    frame.gimbal_az_rad = pointing.az_rad;
    frame.gimbal_el_rad = pointing.el_rad;
    frame.sensor_pose = scenario_.mount.world_from_sensor(frame.start_time_s);

    traced_.set_time_window(frame.start_time_s, frame.end_time_s, scenario_.render.motion_steps);

    const std::size_t rows = static_cast<std::size_t>(raster_.rows());
    const std::size_t cells = static_cast<std::size_t>(raster_.beam_count());
    std::vector<std::uint64_t> rays_by_row(rows, 0);
    aims_.resize(cells);
    if (integrator_.adaptive()) {
        axis_hit_.resize(cells);
        extra_direction_.resize(4 * cells);
        extra_hit_.resize(4 * cells);
    }
    stare_point_.reset();
    if (scenario_.mount.moves() && scenario_.mount.cue_object_id != 0) stare_point_ = stare_point(index, pointing);
    tbb::parallel_for(0, raster_.rows(), [&](int row) {
        rays_by_row[static_cast<std::size_t>(row)] = aim_row(row, pointing, frame.start_time_s);
    });
    if (scenario_.mount.moves()) {
        // The cones of targets are tested from where the sensor was over the frame.
        Eigen::AlignedBox3d origins;
        for (const BeamAim& a : aims_) origins.extend(a.origin_world);
        traced_.set_viewpoint(origins.center(), 0.5 * origins.diagonal().norm());
    }
    if (target_lattice_) target_lattice_->start_frame(pointing, index, frame.start_time_s);
    // Pass 2 in stretches of a line: lines differ in cost (the horizon's against the sky's), and
    // stretches keep both cores busy.
    constexpr int kStepsPerTask = 16;
    const int stretches = (raster_.columns() + kStepsPerTask - 1) / kStepsPerTask;
    std::vector<std::vector<Return>> by_stretch(rows * static_cast<std::size_t>(stretches));
    std::vector<std::uint64_t> rays_by_stretch(by_stretch.size(), 0);
    const bool record_waveforms = scenario_.render.waveforms;
    std::vector<std::vector<WaveformWindow>> windows_by_stretch(record_waveforms ? by_stretch.size() : 0);
    tbb::parallel_for(0, static_cast<int>(by_stretch.size()), [&](int task) {
        const int row = task / stretches, first = (task % stretches) * kStepsPerTask;
        const auto t = static_cast<std::size_t>(task);
        by_stretch[t] = trace_steps(row, first, std::min(first + kStepsPerTask, raster_.columns()), index, rays_by_stretch[t],
                                    record_waveforms ? &windows_by_stretch[t] : nullptr);
    });
    waveforms_last_frame_ = {};
    if (record_waveforms) {
        waveforms_last_frame_ = waveform_header(index, scenario_, receiver_);
        for (auto& piece : windows_by_stretch)
            for (auto& w : piece) waveforms_last_frame_.windows.push_back(std::move(w));
        // Stretches are in raster order already; a triangle sweep's odd lines fired right to left.
        std::stable_sort(waveforms_last_frame_.windows.begin(), waveforms_last_frame_.windows.end(),
                         [](const WaveformWindow& a, const WaveformWindow& b) { return std::tie(a.row, a.column) < std::tie(b.row, b.column); });
    }
    std::vector<std::vector<Return>> by_row(rows);
    for (std::size_t row = 0; row < rows; ++row) {
        std::vector<Return>& returns = by_row[row];
        for (int k = 0; k < stretches; ++k) {
            const auto& piece = by_stretch[row * static_cast<std::size_t>(stretches) + static_cast<std::size_t>(k)];
            returns.insert(returns.end(), piece.begin(), piece.end());
        }
        // A triangle sweep fires odd lines right to left; frames list returns by column. (A
        // line fired left to right is in order already: stable_sort would still allocate.)
        const auto by_column = [](const Return& a, const Return& b) { return a.column < b.column; };
        if (!std::is_sorted(returns.begin(), returns.end(), by_column)) std::stable_sort(returns.begin(), returns.end(), by_column);
    }
    rays_last_frame_ = 0;
    for (const std::uint64_t r : rays_by_row) rays_last_frame_ += r;
    for (const std::uint64_t r : rays_by_stretch) rays_last_frame_ += r;
    std::size_t total = 0;
    for (const auto& r : by_row) total += r.size();
    frame.returns.reserve(total);
    for (auto& r : by_row) frame.returns.insert(frame.returns.end(), r.begin(), r.end());

    frame.ground_truth = ground_truth(0.5 * (frame.start_time_s + frame.end_time_s), frame.returns);
    return frame;
}

}  // namespace ladarsim::sensor_model
