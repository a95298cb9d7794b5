#include "map_scanline.h"

#include <algorithm>
#include <cmath>

#include "ladarsim/scene/scene.h"
#include "map_pieces.h"

namespace ladarsim::sensor_model {

using namespace map_pieces;

MapScanline::MapScanline(const FootprintContext& context, const MapDiscs& discs, int lines, int rays_per_line, const BeamCone* cone)
    : context_(context), discs_(discs), cone_(cone), rays_per_line_(rays_per_line),
      dense_split_(rays_per_line > 0 ? std::max(1, (lines + rays_per_line - 1) / rays_per_line) : 1) {
    const Footprint& footprint = context.shape.footprint();
    const double rho = footprint.max_offset_rad();
    const double ell = context.shape.ellipticity();
    // Strips of equal energy of the axis' Gaussian across [-rho, rho], each line at its median.
    const double cdf_lo = footprint.axis_cdf(-rho), cdf_hi = footprint.axis_cdf(rho);
    const double strip = (cdf_hi - cdf_lo) / lines;
    for (int i = 0; i < lines; ++i) {
        const double x = footprint.axis_offset(cdf_lo + (i + 0.5) * strip);
        const double y_max = std::sqrt(std::max(0.0, rho * rho - x * x));
        lines_.push_back({x, std::tan(x), y_max, std::tan(y_max * ell), strip});
    }
    tan_half_ = 1.01 * std::tan(rho * std::max(1.0, ell)) * std::sqrt(2.0);
}

void MapScanline::chords_on_lines(const Eigen::Matrix3d& R, const Eigen::Vector3d& apex, std::vector<std::vector<DiscChord>>& on_line) const {
    thread_local std::vector<std::uint32_t> candidates;
    discs_.in_cone(apex, R.col(0), tan_half_, context_.max_range_m, candidates);
    on_line.resize(lines_.size());
    for (auto& c : on_line) c.clear();
    for (const std::uint32_t i : candidates) {
        const Eigen::Vector3d p = R.transpose() * (discs_.centre(i) - apex);
        const double r = discs_.radius(i);
        if (!(p.x() > r)) continue;  // holds the sensor's plane: nothing a beam ahead meets
        const Eigen::Vector3d n = R.transpose() * discs_.normal(i);
        const double x_c = std::atan2(p.y(), p.x());
        const double half = std::asin(std::min(1.0, r / std::hypot(p.x(), p.y())));
        auto first = std::lower_bound(lines_.begin(), lines_.end(), x_c - half, [](const Line& l, double x) { return l.x_rad < x; });
        for (auto line = first; line != lines_.end() && line->x_rad <= x_c + half; ++line) {
            DiscChord c;
            if (disc_chord(p, n, r, line->X, line->t_max, c)) {
                c.disc = i;
                on_line[static_cast<std::size_t>(line - lines_.begin())].push_back(c);
            }
        }
    }
}

double MapScanline::visible_pieces(std::vector<std::vector<DiscChord>>& on_line, const FootprintPart& part,
                                   std::vector<VisiblePiece>& pieces, std::vector<std::uint32_t>& line_start) const {
    const double ell = context_.shape.ellipticity();
    pieces.clear();
    line_start.clear();
    double part_weight = 0.0;
    for (std::size_t k = 0; k < lines_.size(); ++k) {
        const Line& line = lines_[k];
        line_start.push_back(static_cast<std::uint32_t>(pieces.size()));
        const bool cut = part.excluded && line.x_rad >= part.excluded->x_lo && line.x_rad <= part.excluded->x_hi;
        if (!cut) {
            lower_envelope(on_line[k], -line.t_max, line.t_max, pieces);
            part_weight += mass(line, -line.t_max, line.t_max);
            continue;
        }
        const double lo = std::clamp(std::tan(part.excluded->y_lo * ell), -line.t_max, line.t_max);
        const double hi = std::clamp(std::tan(part.excluded->y_hi * ell), -line.t_max, line.t_max);
        if (lo > -line.t_max) {
            lower_envelope(on_line[k], -line.t_max, lo, pieces);
            part_weight += mass(line, -line.t_max, lo);
        }
        if (hi < line.t_max) {
            lower_envelope(on_line[k], hi, line.t_max, pieces);
            part_weight += mass(line, hi, line.t_max);
        }
    }
    line_start.push_back(static_cast<std::uint32_t>(pieces.size()));
    return part_weight;
}

double MapScanline::y_of(double t) const { return std::atan(t) / context_.shape.ellipticity(); }

double MapScanline::mass(const Line& line, double ta, double tb) const {
    const Footprint& footprint = context_.shape.footprint();
    return line.weight * (footprint.axis_cdf(y_of(tb)) - footprint.axis_cdf(y_of(ta)));
}

Integration MapScanline::integrate(const BeamSetting& beam, const FootprintPart& part, BeamEchoes& out) const {
    if (beam.media) return {Outcome::declined};
    const Footprint& footprint = context_.shape.footprint();
    const double ell = context_.shape.ellipticity();
    const Eigen::Matrix3d& R = beam.aim.world_from_beam;
    const Eigen::Vector3d& origin = beam.aim.origin_world;

    thread_local std::vector<std::vector<DiscChord>> on_line;
    chords_on_lines(R, origin - context_.settings.origin_world, on_line);
    thread_local std::vector<VisiblePiece> pieces;
    thread_local std::vector<std::uint32_t> line_start;
    const double part_weight = visible_pieces(on_line, part, pieces, line_start);
    if (!(part_weight > 0.0)) return {Outcome::empty};
    const double scale = part.share / part_weight;

    // Rays: what else lies in each cell of a line (or each gap), nearer than the map there.
    struct Cell {
        std::uint32_t line;
        double t_lo, t_hi;
    };
    // Where a target may lie, the reference's cells are as fine across a line as the lines are
    // apart: a bird's wing edge-on is a sliver thinner than a coarse cell, which one discretisation
    // hits (and gives the whole cell) and another misses.
    thread_local TargetsInCone targets;
    std::optional<FootprintRect> outline;
    if (rays_per_line_ > 0 && cone_) {
        cone_->find(beam.aim, targets);
        outline = targets.outline;
    }
    thread_local std::vector<Cell> cells;
    thread_local std::vector<raytrace::Ray> rays;
    thread_local std::vector<std::optional<raytrace::Hit>> hits;
    cells.clear();
    rays.clear();
    for (std::uint32_t k = 0; k < lines_.size(); ++k) {
        const Line& line = lines_[k];
        if (rays_per_line_ > 0) {
            const double c0 = footprint.axis_cdf(-line.y_max_rad), c1 = footprint.axis_cdf(line.y_max_rad);
            const bool across = outline && line.x_rad >= outline->x_lo && line.x_rad <= outline->x_hi;
            for (int j = 0; j < rays_per_line_; ++j) {
                const double ca = c0 + (c1 - c0) * j / rays_per_line_, cb = c0 + (c1 - c0) * (j + 1) / rays_per_line_;
                const bool dense = across && footprint.axis_offset(cb) >= outline->y_lo && footprint.axis_offset(ca) <= outline->y_hi;
                const int n = dense ? dense_split_ : 1;
                for (int s = 0; s < n; ++s) {
                    const double ya = footprint.axis_offset(ca + (cb - ca) * s / n), yb = footprint.axis_offset(ca + (cb - ca) * (s + 1) / n);
                    const double ym = footprint.axis_offset(ca + (cb - ca) * (s + 0.5) / n);
                    if (part.excluded && footprint.contains(*part.excluded, line.x_rad, ym)) continue;
                    const bool first = j == 0 && s == 0, last = j + 1 == rays_per_line_ && s + 1 == n;
                    cells.push_back({k, first ? -line.t_max : std::tan(ya * ell), last ? line.t_max : std::tan(yb * ell)});
                    rays.push_back(context_.ray(beam.aim, line.x_rad, ym));
                }
            }
            continue;
        }
        for (std::uint32_t q = line_start[k]; q < line_start[k + 1]; ++q) {
            const VisiblePiece& gap = pieces[q];
            if (gap.disc != kGapPiece || mass(line, gap.t_lo, gap.t_hi) * scale < kMinGapWeight) continue;
            cells.push_back({k, gap.t_lo, gap.t_hi});
            rays.push_back(context_.ray(beam.aim, line.x_rad, y_of(0.5 * (gap.t_lo + gap.t_hi))));
        }
    }
    hits.resize(rays.size());
    if (!rays.empty()) context_.traced.trace(rays, hits);
    out.rays += static_cast<int>(rays.size());

    const double cut_m = kSpanOverPulseSigma * context_.pulse_sigma_m;
    auto direction_world = [&](const Line& line, double t) { return Eigen::Vector3d(R * Eigen::Vector3d(1.0, line.X, t).normalized()); };
    // A disc's piece of a line, cut where its range span is long against the pulse. Returns its weight.
    auto emit_disc = [&](const Line& line, const VisiblePiece& piece, double ta, double tb) {
        auto range_at = [&](double t) { return std::sqrt(1.0 + line.X * line.X + t * t) / (piece.g0 + piece.g1 * t); };
        const double span = std::abs(range_at(tb) - range_at(ta));
        const int n = std::clamp(static_cast<int>(std::ceil(span / cut_m)), 1, kMaxCuts);
        const Eigen::Vector3d normal = discs_.normal(piece.disc);
        double total = 0.0;
        double cdf_a = footprint.axis_cdf(y_of(ta)), range_a = range_at(ta);
        for (int j = 0; j < n; ++j) {
            const double b = ta + (tb - ta) * (j + 1) / n, t = ta + (tb - ta) * (j + 0.5) / n;
            const double cdf_b = footprint.axis_cdf(y_of(b)), range_b = range_at(b);
            const double weight = scale * line.weight * (cdf_b - cdf_a);
            const double spread = std::abs(range_b - range_a) / std::sqrt(12.0);
            cdf_a = cdf_b;
            range_a = range_b;
            if (!(weight > 0.0)) continue;
            const Eigen::Vector3d d = direction_world(line, t);
            const double range = range_at(t);
            out.surface.push_back({range, weight,
                                   context_.echo_energy_j(weight, discs_.reflectance(piece.disc), std::abs(normal.dot(d)), range, 1.0),
                                   spread, scene::kBackgroundObjectId, origin + range * d, normal.cast<float>(), 0});
            total += weight;
        }
        return total;
    };

    std::size_t c = 0;
    for (std::uint32_t k = 0; k < lines_.size(); ++k) {
        const Line& line = lines_[k];
        for (std::uint32_t q = line_start[k]; q < line_start[k + 1]; ++q) {
            const VisiblePiece& piece = pieces[q];
            if (piece.disc == kGapPiece) continue;
            // Cut the piece at the cells of other objects: where one is nearer, it takes the cell.
            double t = piece.t_lo;
            for (std::size_t j = c; j < cells.size() && cells[j].line == k && t < piece.t_hi; ++j) {
                const Cell& cell = cells[j];
                if (cell.t_hi <= t || !hits[j] || hits[j]->object_id == scene::kBackgroundObjectId) continue;
                const double a = std::max(t, cell.t_lo), b = std::min(piece.t_hi, cell.t_hi);
                if (!(b > a)) continue;
                if (a > t) emit_disc(line, piece, t, a);
                const double tm = 0.5 * (a + b);
                const double map_range = std::sqrt(1.0 + line.X * line.X + tm * tm) / (piece.g0 + piece.g1 * tm);
                if (map_range < hits[j]->range_m) emit_disc(line, piece, a, b);
                t = b;
            }
            if (t < piece.t_hi) emit_disc(line, piece, t, piece.t_hi);
        }
        // Each other object's cell: its weight is what the map left of the cell to it.
        for (; c < cells.size() && cells[c].line == k; ++c) {
            const Cell& cell = cells[c];
            if (!hits[c] || hits[c]->object_id == scene::kBackgroundObjectId) continue;
            double kept = 0.0;
            for (std::uint32_t q = line_start[k]; q < line_start[k + 1]; ++q) {
                const VisiblePiece& piece = pieces[q];
                if (piece.disc == kGapPiece) continue;
                const double a = std::max(piece.t_lo, cell.t_lo), b = std::min(piece.t_hi, cell.t_hi);
                if (!(b > a)) continue;
                const double tm = 0.5 * (a + b);
                const double map_range = std::sqrt(1.0 + line.X * line.X + tm * tm) / (piece.g0 + piece.g1 * tm);
                if (map_range < hits[c]->range_m) kept += mass(line, a, b);
            }
            const double weight = scale * std::max(0.0, mass(line, cell.t_lo, cell.t_hi) - kept);
            if (!(weight > 0.0)) continue;
            const raytrace::Hit& h = *hits[c];
            out.surface.push_back({h.range_m, weight, context_.echo_energy_j(weight, h.reflectance, h.cos_incidence, h.range_m, 1.0), 0.0,
                                   h.object_id, rays[c].origin_world + h.range_m * rays[c].direction, h.normal_world, 0});
        }
    }
    return {Outcome::integrated, part.share};
}

}  // namespace ladarsim::sensor_model
