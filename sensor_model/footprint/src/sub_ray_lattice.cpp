#include "ladarsim/sensor_model/footprint/sub_ray_lattice.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <thread>

#include <Eigen/Geometry>

#include "ladarsim/sensor_model/sensor/beam_geometry.h"
#include "ladarsim/sensor_model/signal/counter_random.h"

namespace ladarsim::sensor_model {

namespace {

constexpr int kTile = 16;  ///< lattice cells along each side of a tile

}  // namespace

double SubRayLattice::overlap(const Footprint& footprint, double ellipticity, const ScanPattern& raster) {
    const double r = footprint.max_offset_rad();
    return std::numbers::pi * r * r * ellipticity / (raster.pitch_az_rad() * raster.pitch_el_rad());
}

SubRayLattice::SubRayLattice(const raytrace::TracedScene& traced, const ScanPattern& raster, const Footprint& footprint,
                             double ellipticity, std::size_t samples_per_footprint, const Eigen::Vector3d& origin_world,
                             const Eigen::Matrix3d& world_from_sensor, double max_range_m, std::uint64_t seed, bool jitter,
                             std::function<double(const raytrace::Hit&)> unit_echo_j)
    : traced_(traced),
      footprint_(footprint),
      ellipticity_(ellipticity),
      origin_world_(origin_world),
      world_from_sensor_(world_from_sensor),
      max_range_m_(max_range_m),
      seed_(seed),
      jitter_(jitter),
      unit_echo_j_(std::move(unit_echo_j)) {
    const double r_max = footprint_.max_offset_rad();
    // As dense as makes the irradiance summed over a whole footprint's sub-rays (1 on the axis) its
    // budget: a cell's area (in footprint coordinates) is the Gaussian's integral, pi w^2 / 2 of
    // the captured share, over the budget. Elevation offsets are footprint offsets times the
    // ellipticity.
    const double w = footprint_.waist_rad();
    const double captured = -std::expm1(-2.0 * r_max * r_max / (w * w));
    step_az_ = std::sqrt(0.5 * std::numbers::pi * w * w * captured / static_cast<double>(std::max<std::size_t>(samples_per_footprint, 1)));
    step_el_ = step_az_ * ellipticity_;
    reach_el_ = 1.01 * r_max * ellipticity_;
    double az_min = 1e300, az_max = -1e300, el_min = 1e300, el_max = -1e300;
    for (int row = 0; row < raster.rows(); ++row) {
        for (int k = 0; k < raster.columns(); ++k) {
            const RasterBeam b = raster.beam(row, k);
            az_min = std::min(az_min, b.az_offset_rad);
            az_max = std::max(az_max, b.az_offset_rad);
            el_min = std::min(el_min, b.el_offset_rad);
            el_max = std::max(el_max, b.el_offset_rad);
        }
    }
    const double steepest = std::max(std::abs(el_min), std::abs(el_max)) + reach_el_;
    if (!(steepest < 0.5 * std::numbers::pi - 0.01)) throw std::invalid_argument("sub-ray lattice: a footprint reaches the pole");
    const double reach_az = 1.01 * r_max / std::cos(steepest);
    az_lo_ = az_min - reach_az - step_az_;
    el_lo_ = el_min - reach_el_ - step_el_;
    columns_ = static_cast<int>(std::ceil((az_max + reach_az + step_az_ - az_lo_) / step_az_));
    rows_ = static_cast<int>(std::ceil((el_max + reach_el_ + step_el_ - el_lo_) / step_el_));
    tile_columns_ = (columns_ + kTile - 1) / kTile;
    tile_rows_ = (rows_ + kTile - 1) / kTile;
    const double points = double(columns_) * double(rows_);
    if (points > kMaxPoints) {
        columns_ = rows_ = tile_columns_ = tile_rows_ = 0;  // not usable: beams keep their own sub-rays
        return;
    }
    points_.resize(static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_));
    tile_state_ = std::make_unique<std::atomic<std::uint8_t>[]>(static_cast<std::size_t>(tile_columns_ * tile_rows_));
}

void SubRayLattice::start_frame(GimbalPointing pointing, std::uint64_t frame) {
    world_from_gimbal_ = world_from_sensor_ * sensor_from_beam(pointing, 0.0, 0.0);
    frame_ = frame;
    for (int t = 0; t < tile_columns_ * tile_rows_; ++t) tile_state_[static_cast<std::size_t>(t)].store(0, std::memory_order_relaxed);
}

int SubRayLattice::ensure_tile(std::size_t t) const {
    std::atomic<std::uint8_t>& state = tile_state_[t];
    std::uint8_t now = state.load(std::memory_order_acquire);
    if (now == 2) return 0;
    if (now == 0 && state.compare_exchange_strong(now, 1, std::memory_order_acq_rel)) {
        try {
            const int rays = trace_tile(t);
            state.store(2, std::memory_order_release);
            return rays;
        } catch (...) {
            state.store(3, std::memory_order_release);
            throw;
        }
    }
    // Another thread traces it: a tile is a few hundred rays, so waiting beats tracing it twice.
    while ((now = state.load(std::memory_order_acquire)) == 1) std::this_thread::yield();
    if (now == 3) throw std::runtime_error("sub-ray lattice: tracing a tile failed on another thread");
    return 0;
}

int SubRayLattice::trace_tile(std::size_t t) const {
    const int row0 = static_cast<int>(t) / tile_columns_ * kTile, column0 = static_cast<int>(t) % tile_columns_ * kTile;
    const int row1 = std::min(row0 + kTile, rows_), column1 = std::min(column0 + kTile, columns_);
    thread_local std::vector<raytrace::Ray> rays;
    thread_local std::vector<std::optional<raytrace::Hit>> hits;
    thread_local std::vector<std::size_t> index;
    rays.clear();
    index.clear();
    for (int row = row0; row < row1; ++row) {
        for (int column = column0; column < column1; ++column) {
            const std::size_t p = static_cast<std::size_t>(row) * static_cast<std::size_t>(columns_) + static_cast<std::size_t>(column);
            double ja = 0.5, je = 0.5;
            if (jitter_) {
                const auto u = uniform4(seed_, RandomStream::lattice_jitter, frame_, static_cast<std::uint32_t>(p), 0);
                ja = u[0];
                je = u[1];
            }
            const double az = az_lo_ + (column + ja) * step_az_, el = el_lo_ + (row + je) * step_el_;
            Point& point = points_[p];
            point.direction_world = world_from_gimbal_ * direction_towards({az, el});
            raytrace::Ray ray;
            ray.origin_world = origin_world_;
            ray.direction = point.direction_world;
            ray.max_range_m = max_range_m_;
            rays.push_back(ray);
            index.push_back(p);
        }
    }
    hits.resize(rays.size());
    traced_.trace_static(rays, hits);
    for (std::size_t i = 0; i < rays.size(); ++i) points_[index[i]].met(hits[i], origin_world_, unit_echo_j_);
    return static_cast<int>(rays.size());
}

void SubRayLattice::gather(const Eigen::Matrix3d& world_from_beam, std::uint32_t cell, const std::optional<FootprintRect>& excluded,
                           double share, BeamEchoes& out) const {
    // The beam's axis in the lattice's angles, and the cells its footprint can reach.
    const Eigen::Vector3d axis = world_from_gimbal_.transpose() * world_from_beam.col(0);
    const double az0 = std::atan2(axis.y(), axis.x()), el0 = std::asin(std::clamp(axis.z(), -1.0, 1.0));
    const double r_max = footprint_.max_offset_rad();
    const double reach_az = 1.01 * r_max / std::cos(std::min(std::abs(el0) + reach_el_, 0.5 * std::numbers::pi - 0.01));
    const int c_lo = std::clamp(static_cast<int>(std::floor((az0 - reach_az - az_lo_) / step_az_)), 0, columns_ - 1);
    const int c_hi = std::clamp(static_cast<int>(std::floor((az0 + reach_az - az_lo_) / step_az_)), 0, columns_ - 1);
    const int r_lo = std::clamp(static_cast<int>(std::floor((el0 - reach_el_ - el_lo_) / step_el_)), 0, rows_ - 1);
    const int r_hi = std::clamp(static_cast<int>(std::floor((el0 + reach_el_ - el_lo_) / step_el_)), 0, rows_ - 1);
    for (int tr = r_lo / kTile; tr <= r_hi / kTile; ++tr)
        for (int tc = c_lo / kTile; tc <= c_hi / kTile; ++tc) out.rays += ensure_tile(static_cast<std::size_t>(tr * tile_columns_ + tc));

    // Sub-rays are taken in proportion to the beam's irradiance at their cells' centres, by
    // systematic sampling: where the running sum passes one of the thresholds k + u. The lattice is
    // as dense as makes a whole footprint's sum its budget, and no cell's irradiance exceeds 1, so
    // none is taken twice; the sub-rays taken are as dense as the beam's energy, as a stratified
    // footprint's are, so each echo's pulse stretches to its neighbours in range as the receiver's
    // model of a sampled surface expects (docs/sensor.md). At the centres the irradiance is
    // separable: across a footprint the raster's angles are its offsets to 1e-5 of themselves.
    const double w = footprint_.waist_rad();
    const double inverse_w2 = 2.0 / (w * w);
    const double cos_el0 = std::cos(el0);
    thread_local std::vector<double> across_here;
    std::vector<double>& across = across_here;
    across.resize(static_cast<std::size_t>(c_hi - c_lo + 1));
    for (int column = c_lo; column <= c_hi; ++column) {
        const double x = (az_lo_ + (column + 0.5) * step_az_ - az0) * cos_el0;
        across[static_cast<std::size_t>(column - c_lo)] = std::exp(-x * x * inverse_w2);
    }
    const double r2 = r_max * r_max;
    const double u = uniform4(seed_, RandomStream::lattice_choice, frame_, cell, 0)[0];
    thread_local std::vector<std::pair<std::size_t, double>> taken_here;
    std::vector<std::pair<std::size_t, double>>& taken = taken_here;  ///< sub-ray, irradiance at its cell's centre
    taken.clear();
    double sum = 0.0, next = u;
    for (int row = r_lo; row <= r_hi; ++row) {
        const double y = (el_lo_ + (row + 0.5) * step_el_ - el0) / ellipticity_;
        if (y * y > r2) continue;
        const double up = std::exp(-y * y * inverse_w2);
        // The columns whose centres lie within the truncation on this row.
        const double half = std::sqrt(r2 - y * y) / cos_el0;
        const int first = std::max(c_lo, static_cast<int>(std::ceil((az0 - half - az_lo_) / step_az_ - 0.5)));
        const int last = std::min(c_hi, static_cast<int>(std::floor((az0 + half - az_lo_) / step_az_ - 0.5)));
        const std::size_t row_start = static_cast<std::size_t>(row) * static_cast<std::size_t>(columns_);
        const double* row_across = across.data() - c_lo;
        for (int column = first; column <= last; ++column) {
            const double irradiance = row_across[column] * up;
            sum += irradiance;
            if (sum < next) continue;
            next += 1.0;
            taken.emplace_back(row_start + static_cast<std::size_t>(column), irradiance);
        }
    }
    // Each carries the irradiance at its own (jittered) place over that at its centre, and all of
    // them `share` (those that met nothing too: the sky's part). The exact offsets also decide the
    // truncation and what `excluded` holds.
    const Eigen::Matrix3d beam_from_world = world_from_beam.transpose();
    double total = 0.0;
    for (auto& [p, irradiance] : taken) {
        const Eigen::Vector3d v = beam_from_world * points_[p].direction_world;
        const double x = small_atan(v.y() / v.x()), y = small_atan(v.z() / v.x()) / ellipticity_;
        const bool kept = v.x() > 0.0 && footprint_.within_truncation(x, y) && !(excluded && footprint_.contains(*excluded, x, y));
        irradiance = kept ? std::exp(-(x * x + y * y) * inverse_w2) / irradiance : 0.0;
        total += irradiance;
    }
    if (!(total > 0.0)) return;
    const double scale = share / total;
    for (const auto& [p, ratio] : taken) {
        const Point& point = points_[p];
        if (!point.hit || ratio == 0.0) continue;
        const double weight = ratio * scale;
        out.surface.push_back({point.range_m, weight, point.unit_echo_j * weight, 0.0, point.object_id, point.point_world,
                               point.normal_world, 0});
    }
}

}  // namespace ladarsim::sensor_model
