#include "map_rows.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "ladarsim/scene/scene.h"
#include "ladarsim/sensor_model/footprint/disc_chords.h"
#include "map_pieces.h"

namespace ladarsim::sensor_model {

namespace {

/// Lines whose discs one query of the map's hierarchy finds (a cone around them all).
constexpr int kLinesPerQuery = 16;
/// A row's lines, footprints included, within this of its middle azimuth: a line is (1, tan of its
/// azimuth from the middle, t), which turns back at a quarter turn (a spinning sensor's row goes
/// all the way round: the VLP-16 found a third of its recorded returns again).
constexpr double kMaxAzimuthFromMiddle = M_PI / 3.0;

}  // namespace

using namespace map_pieces;

bool MapRows::applicable(const ScanPattern& raster, const BeamShape& shape) {
    if (raster.columns() < 2) return false;
    const double pitch = std::abs(raster.beam(0, 1).az_offset_rad - raster.beam(0, 0).az_offset_rad);
    if (!(pitch > 0.0) || pitch >= 2.0 * shape.footprint().max_offset_rad()) return false;
    for (int row = 0; row < raster.rows(); ++row) {
        const RasterBeam first = raster.beam(row, 0);
        double lo = first.az_offset_rad, hi = first.az_offset_rad;
        for (int step = 1; step < raster.columns(); ++step) {
            const RasterBeam b = raster.beam(row, step), before = raster.beam(row, step - 1);
            if (b.el_offset_rad != first.el_offset_rad) return false;
            if (std::abs(std::abs(b.az_offset_rad - before.az_offset_rad) - pitch) > 1e-9 * pitch) return false;
            lo = std::min(lo, b.az_offset_rad);
            hi = std::max(hi, b.az_offset_rad);
        }
        const double reach = shape.footprint().max_offset_rad() / std::cos(first.el_offset_rad) + pitch;
        if (!(0.5 * (hi - lo) + reach < kMaxAzimuthFromMiddle)) return false;
    }
    return true;
}

MapRows::MapRows(const FootprintContext& context, const MapDiscs& discs, const ScanPattern& raster, int lines_per_pitch)
    : context_(context), discs_(discs), columns_(raster.columns()) {
    line_pitch_rad_ = std::abs(raster.beam(0, 1).az_offset_rad - raster.beam(0, 0).az_offset_rad) / lines_per_pitch;
    const double rho = context.shape.footprint().max_offset_rad();
    rows_.resize(static_cast<std::size_t>(raster.rows()));
    azimuth_of_cell_.resize(static_cast<std::size_t>(raster.rows() * columns_));
    for (int r = 0; r < raster.rows(); ++r) {
        Row& row = rows_[static_cast<std::size_t>(r)];
        double lo = 0.0, hi = 0.0;
        for (int step = 0; step < columns_; ++step) {
            const RasterBeam b = raster.beam(r, step);
            azimuth_of_cell_[static_cast<std::size_t>(r * columns_ + step)] = b.az_offset_rad;
            lo = step == 0 ? b.az_offset_rad : std::min(lo, b.az_offset_rad);
            hi = step == 0 ? b.az_offset_rad : std::max(hi, b.az_offset_rad);
            row.elevation_rad = b.el_offset_rad;
        }
        // Lines half a line pitch off every beam's axis (offsets are then the same set for all),
        // as far beyond the outer beams as a footprint reaches (x is about azimuth * cos(elevation)).
        const int beyond = static_cast<int>(std::ceil(rho / std::cos(row.elevation_rad) / line_pitch_rad_)) + 1;
        row.first_azimuth_rad = lo - beyond * line_pitch_rad_;
        const int count = static_cast<int>(std::lround((hi - lo) / line_pitch_rad_)) + 2 * beyond;
        const double middle = 0.5 * (lo + hi);
        row.middle_azimuth_rad = middle;
        row.world_from_row = Eigen::Matrix3d::Identity();
        for (int j = 0; j < count; ++j) {
            const double azimuth = row.first_azimuth_rad + (j + 0.5) * line_pitch_rad_;
            const double X = std::tan(azimuth - middle);
            row.lines.push_back({azimuth, X, std::sqrt(1.0 + X * X), 0});
        }
        row.lines.push_back({0.0, 0.0, 1.0, 0});  // closes the last line's pieces
    }
}

double MapRows::t_of(const Row& row, const Line& line, double y) const {
    return std::tan(row.elevation_rad + y * context_.shape.ellipticity()) * line.s;
}

void MapRows::add_disc_piece(const Row& row, const Line& line, double ta, double tb, std::uint32_t disc, double g0, double g1,
                             std::vector<Piece>& out) const {
    const Footprint& footprint = context_.shape.footprint();
    const double ell = context_.shape.ellipticity();
    auto range_at = [&](double t) { return std::sqrt(1.0 + line.X * line.X + t * t) / (g0 + g1 * t); };
    auto y_at = [&](double t) { return (std::atan(t / line.s) - row.elevation_rad) / ell; };
    const double span = std::abs(range_at(tb) - range_at(ta));
    const int n = std::clamp(static_cast<int>(std::ceil(span / (kSpanOverPulseSigma * context_.pulse_sigma_m))), 1, kMaxCuts);
    const Eigen::Vector3d normal = discs_.normal(disc);
    double y_a = y_at(ta), cdf_a = footprint.axis_cdf(y_a), range_a = range_at(ta);
    for (int j = 0; j < n; ++j) {
        const double b = ta + (tb - ta) * (j + 1) / n, t = ta + (tb - ta) * (j + 0.5) / n;
        const double y_b = y_at(b), cdf_b = footprint.axis_cdf(y_b), range_b = range_at(b);
        const Eigen::Vector3d d = row.world_from_row * Eigen::Vector3d(1.0, line.X, t).normalized();
        const double range = range_at(t);
        const double cos_incidence = std::abs(normal.dot(d));
        out.push_back({y_a, y_b, cdf_a, cdf_b, range, std::abs(range_b - range_a) / std::sqrt(12.0),
                       context_.echo_energy_j(1.0, discs_.reflectance(disc), cos_incidence, range, 1.0), g0, g1,
                       context_.settings.origin_world + range * d, normal.cast<float>(), scene::kBackgroundObjectId, true});
        y_a = y_b;
        cdf_a = cdf_b;
        range_a = range_b;
    }
}

void MapRows::start_row(int row_index, const Eigen::Matrix3d& world_from_gimbal) {
    Row& row = rows_[static_cast<std::size_t>(row_index)];
    const Footprint& footprint = context_.shape.footprint();
    const double rho = footprint.max_offset_rad(), ell = context_.shape.ellipticity();
    const std::size_t lines = row.lines.size() - 1;
    const double middle = row.middle_azimuth_rad;
    row.world_from_row = world_from_gimbal * Eigen::AngleAxisd(middle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const double e_lo = row.elevation_rad - rho * ell, e_hi = row.elevation_rad + rho * ell;

    thread_local std::vector<std::vector<DiscChord>> on_line;
    thread_local std::vector<std::uint32_t> candidates;
    thread_local std::vector<VisiblePiece> visible;
    thread_local std::vector<raytrace::Ray> rays;
    thread_local std::vector<std::size_t> ray_piece;
    thread_local std::vector<std::optional<raytrace::Hit>> hits;
    on_line.resize(lines);
    for (auto& c : on_line) c.clear();
    const double ce = std::cos(row.elevation_rad), se = std::sin(row.elevation_rad);
    for (std::size_t first = 0; first < lines; first += kLinesPerQuery) {
        const std::size_t last = std::min(lines, first + kLinesPerQuery);
        // A cone around these lines' stretch of the row (azimuth half-width a, elevation half-height b).
        const double az = 0.5 * (row.lines[first].azimuth_rad + row.lines[last - 1].azimuth_rad);
        const double a = (0.5 * static_cast<double>(last - first) + 0.5) * line_pitch_rad_ * ce, b = rho * ell;
        const Eigen::Vector3d axis = world_from_gimbal * Eigen::Vector3d(ce * std::cos(az), ce * std::sin(az), se);
        discs_.in_cone(Eigen::Vector3d::Zero(), axis, 1.01 * std::tan(std::hypot(a, b)), context_.max_range_m, candidates);
        const double lo = row.lines[first].azimuth_rad - middle, step = line_pitch_rad_;
        for (const std::uint32_t i : candidates) {
            const Eigen::Vector3d p = row.world_from_row.transpose() * discs_.centre(i);
            const double r = discs_.radius(i);
            if (!(p.x() > r)) continue;  // holds the sensor's plane: nothing a beam ahead meets
            const Eigen::Vector3d n = row.world_from_row.transpose() * discs_.normal(i);
            const double x_c = std::atan2(p.y(), p.x());
            const double half = std::asin(std::min(1.0, r / std::hypot(p.x(), p.y())));
            // Lines k of this stretch at lo + (k - first) * step within [x_c - half, x_c + half].
            const auto k_lo = static_cast<std::ptrdiff_t>(std::ceil((x_c - half - lo) / step));
            const auto k_hi = static_cast<std::ptrdiff_t>(std::floor((x_c + half - lo) / step));
            const auto span = static_cast<std::ptrdiff_t>(last - first);
            for (std::ptrdiff_t m = std::max<std::ptrdiff_t>(0, k_lo); m <= std::min(span - 1, k_hi); ++m) {
                const std::size_t k = first + static_cast<std::size_t>(m);
                const Line& line = row.lines[k];
                DiscChord c;
                if (disc_chord(p, n, r, line.X, std::tan(e_lo) * line.s, std::tan(e_hi) * line.s, c)) {
                    c.disc = i;
                    on_line[k].push_back(c);
                }
            }
        }
    }
    row.pieces.clear();
    rays.clear();
    ray_piece.clear();
    for (std::size_t k = 0; k < lines; ++k) {
        Line& line = row.lines[k];
        line.first_piece = static_cast<std::uint32_t>(row.pieces.size());
        visible.clear();
        lower_envelope(on_line[k], std::tan(e_lo) * line.s, std::tan(e_hi) * line.s, visible);
        for (const VisiblePiece& v : visible) {
            if (v.disc != kGapPiece) {
                add_disc_piece(row, line, v.t_lo, v.t_hi, v.disc, v.g0, v.g1, row.pieces);
                continue;
            }
            // What the static scene shows through the gap: one ray at its middle.
            const double y_a = (std::atan(v.t_lo / line.s) - row.elevation_rad) / ell;
            const double y_b = (std::atan(v.t_hi / line.s) - row.elevation_rad) / ell;
            row.pieces.push_back({y_a, y_b, footprint.axis_cdf(y_a), footprint.axis_cdf(y_b), 0.0, 0.0, 0.0, 0.0, 0.0,
                                  Eigen::Vector3d::Zero(), Eigen::Vector3f::Zero(), kGapPiece, false});
            raytrace::Ray ray;
            ray.origin_world = context_.settings.origin_world;
            ray.direction = row.world_from_row * Eigen::Vector3d(1.0, line.X, 0.5 * (v.t_lo + v.t_hi)).normalized();
            ray.time_s = 0.0;
            ray.max_range_m = context_.max_range_m;
            rays.push_back(ray);
            ray_piece.push_back(row.pieces.size() - 1);
        }
    }
    row.lines[lines].first_piece = static_cast<std::uint32_t>(row.pieces.size());
    row.piece_y_hi.resize(row.pieces.size());
    for (std::size_t i = 0; i < row.pieces.size(); ++i) row.piece_y_hi[i] = row.pieces[i].y_hi;
    hits.resize(rays.size());
    if (!rays.empty()) context_.traced.trace_static(rays, hits);
    for (std::size_t q = 0; q < rays.size(); ++q) {
        if (!hits[q] || hits[q]->object_id == scene::kBackgroundObjectId) continue;
        const raytrace::Hit& h = *hits[q];
        Piece& gap = row.pieces[ray_piece[q]];
        gap.object_id = h.object_id;
        gap.range_m = h.range_m;
        gap.energy_per_weight = context_.echo_energy_j(1.0, h.reflectance, h.cos_incidence, h.range_m, 1.0);
        gap.point_world = rays[q].origin_world + h.range_m * rays[q].direction;
        gap.normal_world = h.normal_world;
    }
}

Integration MapRows::integrate(const BeamSetting& beam, const FootprintPart& part, BeamEchoes& out) const {
    if (beam.media) return {Outcome::declined};
    const Footprint& footprint = context_.shape.footprint();
    const double rho = footprint.max_offset_rad();
    const Row& row = rows_[beam.aim.cell / static_cast<std::uint32_t>(columns_)];
    const double azimuth = azimuth_of_cell_[beam.aim.cell];
    const double ce = std::cos(row.elevation_rad), se = std::sin(row.elevation_rad);
    const double half_strip = 0.5 * line_pitch_rad_ * ce;

    // Each line the footprint crosses: its strip's weight across, and the stretches along it the
    // part covers (one, or two about an excluded rectangle), found before any echo so that the
    // echoes carry part.share between them.
    struct Stretch {
        std::uint32_t line;
        double across;        ///< the strip's Gaussian mass across the line
        double y_lo, y_hi, cdf_lo, cdf_hi;
    };
    thread_local std::vector<Stretch> stretches;
    stretches.clear();
    double part_weight = 0.0;
    const double reach = (rho + half_strip) / ce + line_pitch_rad_;
    const auto j_lo = static_cast<std::size_t>(std::max(0.0, std::floor((azimuth - reach - row.first_azimuth_rad) / line_pitch_rad_)));
    const std::size_t lines = row.lines.size() - 1;
    for (std::size_t j = j_lo; j < lines && row.lines[j].azimuth_rad <= azimuth + reach; ++j) {
        const double delta = row.lines[j].azimuth_rad - azimuth;
        // The line's offset across the footprint at the beam's elevation.
        const double x = std::atan(ce * std::sin(delta) / (ce * ce * std::cos(delta) + se * se));
        if (!(std::abs(x) < rho) || x < part.rect.x_lo || x > part.rect.x_hi) continue;
        const double across = footprint.axis_cdf(std::min(x + half_strip, rho)) - footprint.axis_cdf(std::max(x - half_strip, -rho));
        const double y_max = std::sqrt(rho * rho - x * x);
        // Along the line, the footprint's chord within the part's rectangle (the square: all of it).
        const double y_bottom = std::max(-y_max, part.rect.y_lo), y_top = std::min(y_max, part.rect.y_hi);
        if (!(y_top > y_bottom)) continue;
        const double c_max = footprint.axis_cdf(y_top), c_min = footprint.axis_cdf(y_bottom);
        auto add = [&](double ya, double ca, double yb, double cb) {
            if (!(yb > ya)) return;
            stretches.push_back({static_cast<std::uint32_t>(j), across, ya, yb, ca, cb});
            part_weight += across * (cb - ca);
        };
        if (part.excluded && x >= part.excluded->x_lo && x <= part.excluded->x_hi) {
            const double e_lo = std::clamp(part.excluded->y_lo, y_bottom, y_top), e_hi = std::clamp(part.excluded->y_hi, y_bottom, y_top);
            add(y_bottom, c_min, e_lo, footprint.axis_cdf(e_lo));
            add(e_hi, footprint.axis_cdf(e_hi), y_top, c_max);
        } else {
            add(y_bottom, c_min, y_top, c_max);
        }
    }
    if (!(part_weight > 0.0)) return {Outcome::empty};
    const double scale = part.share / part_weight;

    for (const Stretch& s : stretches) {
        const Line& line = row.lines[s.line];
        const double* y_hi = row.piece_y_hi.data();
        const Piece* end = row.pieces.data() + row.lines[s.line + 1].first_piece;
        const Piece* p = row.pieces.data() + (std::upper_bound(y_hi + line.first_piece, y_hi + row.lines[s.line + 1].first_piece, s.y_lo) - y_hi);
        for (; p != end && p->y_lo < s.y_hi; ++p) {
            if (p->object_id == kGapPiece) continue;
            const bool clipped_lo = p->y_lo < s.y_lo, clipped_hi = p->y_hi > s.y_hi;
            const double c_lo = clipped_lo ? s.cdf_lo : p->cdf_lo, c_hi = clipped_hi ? s.cdf_hi : p->cdf_hi;
            const double weight = scale * s.across * (c_hi - c_lo);
            if (!(weight > 0.0)) continue;
            if (!p->disc) {
                if (weight < kMinGapWeight) continue;
                out.surface.push_back({p->range_m, weight, weight * p->energy_per_weight, 0.0, p->object_id, p->point_world, p->normal_world, 0});
                continue;
            }
            if (!clipped_lo && !clipped_hi) {
                out.surface.push_back({p->range_m, weight, weight * p->energy_per_weight, p->spread_m, p->object_id, p->point_world,
                                       p->normal_world, 0});
                continue;
            }
            // A piece the footprint's rim or an excluded target cuts: its range over what is left.
            const double ta = t_of(row, line, clipped_lo ? s.y_lo : p->y_lo), tb = t_of(row, line, clipped_hi ? s.y_hi : p->y_hi);
            auto range_at = [&](double t) { return std::sqrt(1.0 + line.X * line.X + t * t) / (p->g0 + p->g1 * t); };
            const double t = 0.5 * (ta + tb), range = range_at(t);
            const Eigen::Vector3d d = row.world_from_row * Eigen::Vector3d(1.0, line.X, t).normalized();
            out.surface.push_back({range, weight, weight * p->energy_per_weight * (p->range_m * p->range_m) / (range * range),
                                   std::abs(range_at(tb) - range_at(ta)) / std::sqrt(12.0), p->object_id,
                                   context_.settings.origin_world + range * d, p->normal_world, 0});
        }
    }
    return {Outcome::integrated, part.share};
}

}  // namespace ladarsim::sensor_model
