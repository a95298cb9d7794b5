#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "ladarsim/dataset/frame.h"
#include "ladarsim/raytrace/traced_scene.h"
#include "ladarsim/sensor_model/signal/beam_receiver.h"
#include "ladarsim/sensor_model/signal/echo_radiometry.h"
#include "ladarsim/sensor_model/footprint/beam.h"
#include "ladarsim/sensor_model/footprint/footprint_integrator.h"
#include "ladarsim/sensor_model/sensor/scan_pattern.h"
#include "ladarsim/sensor_model/sensor/gimbal.h"
#include "ladarsim/sensor_model/render/scenario.h"
#include "ladarsim/sensor_model/footprint/target_lattice.h"

namespace ladarsim::sensor_model {

/// Turns a scenario into frames: fires every beam of the raster at its own time, integrates the
/// echo energy over its footprint (FootprintIntegrator), gathers the echoes into the distinct
/// surfaces along the beam and hands them to the BeamReceiver, which reports what the detector
/// sees (docs/physics.md).
///
/// With adaptive footprints a frame takes two passes: first every beam's axis is traced (one
/// coherent stream per raster line, plus extra probes where the raster leaves a footprint's edge
/// uncovered), then each beam integrates its footprint knowing what its own and its neighbours'
/// axes met: beams are much closer together than their footprints are wide, so those probes
/// tell, for free, whether a footprint lies on one surface.
///
/// Frames are independent given the scenario and seed (the gimbal's pointing is replayed from
/// frame 0), and beams are traced in parallel with results that do not depend on thread count.
class FrameRenderer {
public:
    explicit FrameRenderer(const Scenario& scenario);

    Frame render(std::uint64_t index);
    /// Frame `index` with the gimbal held at `pointing` instead of where the cue takes it.
    Frame render_at(std::uint64_t index, GimbalPointing pointing);

    double frame_start_s(std::uint64_t index) const;
    GimbalPointing gimbal_pointing(std::uint64_t index);
    const ScanPattern& raster() const { return raster_; }
    /// Rays traced for the last frame rendered (probes and sub-rays): the cost of its accuracy.
    std::uint64_t rays_last_frame() const { return rays_last_frame_; }
    /// The last frame's full waveforms, by (row, column) and then range, when the scenario asks
    /// for them (render.waveforms); empty otherwise. Taken: moved out (megabytes a frame), not copied.
    FrameWaveforms take_waveforms() { return std::move(waveforms_last_frame_); }
    /// The scene as traced (for benchmarks: record its rays, trace them again raw).
    raytrace::TracedScene& traced() { return traced_; }

private:
    /// A neighbouring beam whose axis falls inside a beam's footprint (or just beyond it, a
    /// sentinel): raster steps and offset.
    struct Neighbour {
        int d_row, d_column;
        double x_rad, y_rad;
        double irradiance;
        bool inside;  ///< within the footprint's truncation: a probe, not a sentinel
    };
    /// `gimbal`: the pointing's rotation, AngleAxis(az, z) * AngleAxis(-el, y); `world_from_sensor`
    /// and `origin_world`: the sensor's rotation and place at the beam's time `time_s`.
    BeamAim aim(const RasterBeam& beam, int step, const Eigen::Quaterniond& gimbal, const Eigen::Matrix3d& world_from_sensor,
                const Eigen::Vector3d& origin_world, double time_s) const;
    /// The same on a moving platform: the sensor's pose at the beam's time, and a cued gimbal
    /// stabilised on the frame's stare point (stare_point_).
    BeamAim aim_moving(const RasterBeam& beam, int step, GimbalPointing pointing, double frame_start_s) const;
    /// Where a cued gimbal on a moving platform stares during frame `index` (pointing as it starts):
    /// the point along its line of sight at the cue's distance.
    Eigen::Vector3d stare_point(std::uint64_t index, GimbalPointing pointing) const;
    void find_neighbours();
    /// Pass 1: where and when the beams of one raster line fire and, for adaptive footprints,
    /// their axes and extra probes traced. Returns the rays traced.
    std::uint64_t aim_row(int row, GimbalPointing pointing, double frame_start_s);
    /// Pass 2: the returns of steps [first_step, end_step) of one raster line, in firing order; adds
    /// the rays traced to `rays`.
    /// With `windows` set, also appends the beams' sampled waveforms to it.
    std::vector<Return> trace_steps(int row, int first_step, int end_step, std::uint64_t frame, std::uint64_t& rays,
                                    std::vector<WaveformWindow>* windows) const;
    std::vector<GroundTruthObject> ground_truth(double time_s, const std::vector<Return>& returns) const;
    GimbalPointing cue_pointing(double time_s) const;

    const Scenario& scenario_;
    raytrace::TracedScene traced_;
    const ScanPattern& raster_;
    BeamReceiver receiver_;
    EchoRadiometry radiometry_;
    FootprintIntegrator integrator_;
    /// Sub-rays over a lone target shared by the footprints of a line (null where they would not
    /// overlap).
    std::unique_ptr<TargetLattice> target_lattice_;
    std::vector<GimbalPointing> pointing_by_frame_;
    std::vector<Neighbour> neighbours_;
    /// By raster cell (row, column): whether its axis is a probe of the beams whose footprints it
    /// falls in (the raster-wide grid they are thinned to, and its borders; sentinels are not).
    std::vector<std::uint8_t> probe_axis_;
    /// By (row, step): each beam's offset rotations, AngleAxis(az_offset, z) and
    /// AngleAxis(-el_offset, y), found once (a frame composes them with the gimbal's exactly as
    /// sensor_from_beam does, without its four sines and cosines per beam).
    std::vector<std::array<Eigen::Quaterniond, 2>> offset_rotations_;
    Eigen::Matrix3d world_from_sensor_rotation_;  ///< a fixed mount's, found once
    /// On a moving platform with a cue, the frame's stare point (stare_point()).
    std::optional<Eigen::Vector3d> stare_point_;
    /// Per scene object that is animated, the model-frame box over its whole animation, which its
    /// ground truth is drawn from (every return falls inside it); empty for the others (the mesh's).
    std::vector<Eigen::AlignedBox3d> truth_boxes_model_;
    std::vector<std::uint8_t> extra_mask_;          ///< by raster cell (row, column): bit k = extra probe k
    std::array<Eigen::Vector2d, 4> extra_offsets_;  ///< left, right, up, down
    double extra_irradiance_ = 0.0;
    // Pass 1 results, by raster cell (row, column); extra probes at 4 * cell + k.
    std::vector<BeamAim> aims_;
    std::vector<Eigen::Vector3d> extra_direction_;
    std::vector<ProbeHit> axis_hit_, extra_hit_;
    std::uint64_t rays_last_frame_ = 0;
    FrameWaveforms waveforms_last_frame_;
};

/// Centre of an object's model bounds in the world at `time_s`.
Eigen::Vector3d object_centre_world(const scene::SceneObject& object, double time_s);

}  // namespace ladarsim::sensor_model
