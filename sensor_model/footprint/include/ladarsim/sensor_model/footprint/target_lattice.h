#pragma once
// Sub-rays over a target shared by the footprints of one raster line that meet it (docs/sensor.md,
// "Footprint and returns", step 4).
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "ladarsim/raytrace/traced_scene.h"
#include "ladarsim/sensor_model/footprint/footprint.h"
#include "ladarsim/sensor_model/footprint/beam_shape.h"
#include "ladarsim/sensor_model/footprint/footprint_strategy.h"
#include "ladarsim/sensor_model/signal/echo_radiometry.h"
#include "ladarsim/sensor_model/sensor/gimbal.h"
#include "ladarsim/sensor_model/footprint/lattice_sub_ray.h"
#include "ladarsim/sensor_model/sensor/scan_pattern.h"

namespace ladarsim::sensor_model {

/// For each raster line and target, one stratified lattice of sub-rays over the target's outline,
/// in the raster's angles: equal-energy strata of the line's beams in elevation (every beam of a
/// line has the same elevation), uniform ones in azimuth. Every beam of the line whose cone meets
/// that target alone (no other target, no medium; FootprintIntegrator::integrate) takes the
/// lattice's sub-rays inside its own view of the outline, each carrying its irradiance over the
/// density it was drawn with, instead of sampling the outline itself: the ~15 footprints of a line
/// that overlap a drone share one set of rays.
///
/// A sub-ray leaves when the line sweeps its azimuth (interpolated between the beams either side),
/// up to a footprint's width of the line from a beam that uses it (in the paper's raster 107 us:
/// 6 mm at 60 m/s). A beam moves the lattice with the target (a translation at its velocity over
/// the line) to where it stood when the beam fired, what met the target exactly: taken as they
/// were, a 0.3 m plate crossing 1 km out at 60 m/s on a raster 5 times slower along its lines than
/// the paper's lost 1.1-1.5 % of its echo to the outline's edges (the footprint's own view of it,
/// at its own time, clipped the moved plate); moved, 0.1 %.
///
/// A lattice is traced when a beam first needs it, once a frame, on whichever thread asks first;
/// its jitter is keyed by (seed, frame, target, line and its place in it), so the result is the same
/// for any thread count.
class TargetLattice final : public FootprintStrategy {
public:
    /// Whether the beams of a raster line overlap enough along it that sharing pays: a footprint
    /// spans at least this many of its beams.
    static constexpr double kMinBeamsAcross = 4.0;
    static bool worthwhile(const Footprint& footprint, const ScanPattern& raster);

    /// `grid_base`: its strata, as many along each axis of a footprint's view of a target as the
    /// integrator's grid for a lone target has (FootprintIntegrator::grid_base()).
    TargetLattice(const raytrace::TracedScene& traced, const ScanPattern& raster, const BeamShape& shape,
                  const EchoRadiometry& radiometry, int grid_base,
                  const Eigen::Vector3d& origin_world, const Eigen::Matrix3d& world_from_sensor, double max_range_m, std::uint64_t seed,
                  bool jitter);
    TargetLattice(const TargetLattice&) = delete;
    TargetLattice& operator=(const TargetLattice&) = delete;

    /// A new frame: the gimbal's pointing for all of it and the frame's start; nothing traced yet.
    void start_frame(GimbalPointing pointing, std::uint64_t frame, double frame_start_s);

    /// Appends the echoes of the beam `aim` from the sub-rays of its line's lattice over target
    /// `object_id` inside `outline` (footprint offsets) and the truncation, adds the rays this
    /// traced to `out.rays`, and returns the share of the beam they sampled. Nothing, with nothing
    /// appended, where the lattice does not hold the outline or holds too few of its sub-rays
    /// there (a footprint's edge across the target): the beam then samples the outline itself.
    /// With `map` (a recorded map's integration over a rectangle, MapRows), the sub-rays that met
    /// the map bring its echoes over the outline instead of their own single ranges.
    std::optional<double> gather(const BeamSetting& beam, std::uint32_t object_id, const FootprintRect& outline, BeamEchoes& out,
                                 const FootprintStrategy* map = nullptr) const;
    /// gather() as a strategy: the beam's lone target (beam.lone_target_id) inside part.rect.
    Integration integrate(const BeamSetting& beam, const FootprintPart& part, BeamEchoes& out) const override;
    /// integrate(), the map's sub-rays by `map` (see gather).
    Integration integrate_over_map(const BeamSetting& beam, const FootprintPart& part, const FootprintStrategy& map, BeamEchoes& out) const;

private:
    struct Point : LatticeSubRay {
        /// The share of the beam it carries per unit of the beam's irradiance where it lands.
        double per_irradiance = 0.0;
        double time_s = 0.0;          ///< when it left
        /// Its stratum about it, in footprint offsets: half its width across the line, and how
        /// far it reaches below and above it along.
        double half_x = 0.0, below_y = 0.0, above_y = 0.0;
    };
    struct Line {
        double el_rad = 0.0;              ///< the line's elevation offset
        double az_lo = 0.0, az_hi = 0.0;  ///< its beams' azimuth offsets
        std::vector<std::pair<double, double>> time_by_az;  ///< (azimuth offset, time offset), by azimuth
    };
    /// One (line, target) lattice of the frame: 0 not traced, 1 being traced, 2 traced, 3 failed.
    struct Slot {
        std::atomic<std::uint8_t> state{0};
        double az_lo = 0.0, az_hi = 0.0, el_lo = 0.0, el_hi = 0.0;  ///< what it covers
        /// The target's velocity while the line fires, and its range (gather moves the lattice
        /// with it).
        Eigen::Vector3d velocity_world = Eigen::Vector3d::Zero();
        double range_m = 0.0;
        int rays = 0;
        std::vector<Point> points;
    };
    const Slot& ensure(int line, std::size_t target, std::uint32_t object_id, int& rays) const;
    void trace_slot(Slot& slot, int line, std::uint32_t object_id) const;
    /// When the line sweeps azimuth `az` (after the frame's start), and how fast that changes
    /// with azimuth (0 beyond its first and last beam, where it is held).
    std::pair<double, double> time_at(const Line& line, double az) const;
    /// Raster angles (azimuth, elevation offsets) of a world direction.
    GimbalPointing raster_angles(const Eigen::Vector3d& direction_world) const;

    const raytrace::TracedScene& traced_;
    const BeamShape& shape_;
    const EchoRadiometry& radiometry_;
    const Footprint& footprint_;
    double ellipticity_;
    int grid_base_;
    Eigen::Vector3d origin_world_;
    Eigen::Matrix3d world_from_sensor_;
    double max_range_m_;
    std::uint64_t seed_;
    bool jitter_;
    int columns_ = 0;
    std::vector<Line> lines_;
    std::unordered_map<std::uint32_t, std::size_t> target_index_;  ///< object id -> its slots' column
    Eigen::Matrix3d world_from_gimbal_ = Eigen::Matrix3d::Identity();
    std::uint64_t frame_ = 0;
    double frame_start_s_ = 0.0;
    mutable std::unique_ptr<Slot[]> slots_;  ///< by (line, target)
};

}  // namespace ladarsim::sensor_model
