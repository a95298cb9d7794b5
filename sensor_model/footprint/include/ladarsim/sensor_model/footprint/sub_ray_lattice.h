#pragma once
// Sub-rays shared by the overlapping footprints of one frame's beams (docs/sensor.md, "Footprint
// and returns", step 6).
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "ladarsim/raytrace/traced_scene.h"
#include "ladarsim/sensor_model/footprint/footprint.h"
#include "ladarsim/sensor_model/footprint/beam.h"
#include "ladarsim/sensor_model/sensor/gimbal.h"
#include "ladarsim/sensor_model/footprint/lattice_sub_ray.h"
#include "ladarsim/sensor_model/sensor/scan_pattern.h"

namespace ladarsim::sensor_model {

/// A jittered lattice of sub-rays over the static scene, in the raster's own angles (azimuth and
/// elevation offsets from the gimbal's pointing). Where a raster's footprints overlap (the paper's
/// LADAR: each point of its field lies in about 27 of them), every beam that integrates its
/// footprint by brute force over a recorded map takes sub-rays of the lattice inside it, in
/// proportion to its irradiance (the lattice is about 4.5 times as dense as those it takes), instead
/// of tracing as many of its own. Within a frame the gimbal holds still and the static scene does
/// not move, so a sub-ray's hit is the same whichever of those beams fires it and when; moving
/// objects are not in the lattice (a footprint samples them itself, inside their outline).
///
/// Tiles of the lattice are traced when a beam first needs them, once a frame, on whichever
/// thread asks first; a sub-ray's jitter is keyed by (seed, frame, its place in the lattice) and a
/// beam's choice by (seed, frame, its raster cell), so the result is the same for any thread count.
class SubRayLattice {
public:
    /// Whether a raster's footprints overlap enough that sharing pays: a point of the field lies in
    /// at least this many of them.
    static constexpr double kMinOverlap = 4.0;
    /// A footprint takes this many times the sub-rays of a stratified footprint at the same
    /// tolerance. Over Autzen (the bench's hard case, 6 frames against 4096 sub-rays) at 1x the
    /// map's count is 3.4 % short where stratified sub-rays leave it 2.5 % short; at 1.5x, 2.2 %, with
    /// first-return range errors smaller than those of the stratified footprints (docs/sensor.md).
    static constexpr double kBudgetOverStratified = 1.5;
    /// A lattice of more sub-rays than this (a wide field of dense, overlapping footprints at a
    /// fine tolerance: over 2 GB) is not made; its beams keep their own sub-rays.
    static constexpr double kMaxPoints = 2e7;
    /// How many beams' footprints hold a point of the field (on average).
    static double overlap(const Footprint& footprint, double ellipticity, const ScanPattern& raster);

    /// `unit_echo_j(hit)`: the echo energy of a sub-ray carrying the whole beam that meets `hit`.
    SubRayLattice(const raytrace::TracedScene& traced, const ScanPattern& raster, const Footprint& footprint, double ellipticity,
                  std::size_t samples_per_footprint, const Eigen::Vector3d& origin_world, const Eigen::Matrix3d& world_from_sensor,
                  double max_range_m, std::uint64_t seed, bool jitter, std::function<double(const raytrace::Hit&)> unit_echo_j);
    SubRayLattice(const SubRayLattice&) = delete;
    SubRayLattice& operator=(const SubRayLattice&) = delete;

    /// A new frame: the gimbal's pointing for all of it; nothing traced yet.
    void start_frame(GimbalPointing pointing, std::uint64_t frame);

    /// Appends the echoes of the beam aimed by `world_from_beam` (raster cell `cell`, which keys its
    /// draws) from the lattice's sub-rays in its footprint (outside `excluded`, when given): as many
    /// as its budget, taken in proportion to the beam's irradiance, together carrying `share` of it.
    /// Adds the rays this traced to `out.rays`.
    void gather(const Eigen::Matrix3d& world_from_beam, std::uint32_t cell, const std::optional<FootprintRect>& excluded, double share,
                BeamEchoes& out) const;

    /// Whether the lattice was made (see kMaxPoints).
    bool usable() const { return !points_.empty(); }
    /// Sub-rays of the lattice, traced or not.
    std::size_t size() const { return points_.size(); }

private:
    using Point = LatticeSubRay;
    /// Traces tile `t` if no thread has yet; waits for it if another is. Returns the rays traced.
    int ensure_tile(std::size_t t) const;
    int trace_tile(std::size_t t) const;

    const raytrace::TracedScene& traced_;
    Footprint footprint_;
    double ellipticity_;
    Eigen::Vector3d origin_world_;
    Eigen::Matrix3d world_from_sensor_;
    double max_range_m_;
    std::uint64_t seed_;
    bool jitter_;
    std::function<double(const raytrace::Hit&)> unit_echo_j_;
    double az_lo_ = 0.0, el_lo_ = 0.0;  ///< the lattice's corner (offsets from the field centre)
    double step_az_ = 0.0, step_el_ = 0.0;
    int columns_ = 0, rows_ = 0;        ///< lattice cells along azimuth and elevation
    int tile_columns_ = 0, tile_rows_ = 0;
    double reach_el_ = 0.0;             ///< a footprint's half-height in elevation
    Eigen::Matrix3d world_from_gimbal_ = Eigen::Matrix3d::Identity();
    std::uint64_t frame_ = 0;
    mutable std::vector<Point> points_;  ///< by (row, column) of the lattice; filled tile by tile
    /// By tile: 0 not traced, 1 being traced, 2 traced, 3 failed.
    std::unique_ptr<std::atomic<std::uint8_t>[]> tile_state_;
};

}  // namespace ladarsim::sensor_model
