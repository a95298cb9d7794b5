#include "ladarsim/sensor_model/footprint/footprint.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace ladarsim::sensor_model {

namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }

/// Inverse of the standard normal CDF: Acklam's rational approximation, relative error below
/// 1.2e-9 (a sub-ray placed within a nanoradian is placed).
double inverse_normal_cdf(double p) {
    static constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                                   1.383577518672690e+02, -3.066479806614716e+01, 2.506628277459239e+00};
    static constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                                   6.680131188771972e+01, -1.328068155288572e+01};
    static constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                                   -2.549732539343734e+00, 4.374664141464968e+00, 2.938163982698783e+00};
    static constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                                   3.754408661907416e+00};
    constexpr double p_low = 0.02425;
    if (p < p_low || p > 1.0 - p_low) {
        const double q = std::sqrt(-2.0 * std::log(p < p_low ? p : 1.0 - p));
        const double x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
                         ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
        return p < p_low ? x : -x;
    }
    const double q = p - 0.5, r = q * q;
    return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
           (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
}
}  // namespace

Footprint::Footprint(double divergence_rad, int samples, double truncation)
    : waist_rad_(0.5 * divergence_rad),
      max_radius_rad_(truncation * 0.5 * divergence_rad),
      captured_(-std::expm1(-2.0 * truncation * truncation)) {
    if (!(divergence_rad > 0.0) || samples < 1 || !(truncation > 0.0)) {
        throw std::invalid_argument("footprint needs a positive divergence, sample count and truncation");
    }
    const double golden_angle = std::numbers::pi * (3.0 - std::sqrt(5.0));
    const int rings = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(samples)))));
    cells_.reserve(static_cast<std::size_t>(samples));
    int first = 0;
    for (int ring = 0; ring < rings; ++ring) {
        const int in_ring = samples / rings + (ring < samples % rings ? 1 : 0);
        const double lo = captured_ * first / samples;
        const double hi = captured_ * (first + in_ring) / samples;
        const double sector = kTwoPi / in_ring;
        const double turn = golden_angle * ring;
        for (int k = 0; k < in_ring; ++k) {
            cells_.push_back({lo, hi, turn + k * sector, turn + (k + 1) * sector});
        }
        first += in_ring;
    }
}

SubRay Footprint::place(const FootprintRegion& cell, double u_energy, double u_angle, double weight) const {
    // Invert the enclosed energy F(r) = 1 - exp(-2 r^2 / w^2).
    const double energy = cell.energy_lo + u_energy * (cell.energy_hi - cell.energy_lo);
    const double radius = waist_rad_ * std::sqrt(-0.5 * std::log1p(-energy));
    const double angle = cell.angle_lo_rad + u_angle * (cell.angle_hi_rad - cell.angle_lo_rad);
    return {radius * std::cos(angle), radius * std::sin(angle), weight};
}

void Footprint::fixed(std::span<SubRay> out) const {
    const double weight = 1.0 / static_cast<double>(cells_.size());
    for (std::size_t i = 0; i < cells_.size(); ++i) {
        // A lone sample stands for the whole disc: its natural place is the beam axis.
        out[i] = cells_.size() == 1 ? SubRay{0.0, 0.0, 1.0} : place(cells_[i], 0.5, 0.5, weight);
    }
}

void Footprint::jittered(std::span<SubRay> out, std::span<const double> uniforms) const {
    const double weight = 1.0 / static_cast<double>(cells_.size());
    for (std::size_t i = 0; i < cells_.size(); ++i) {
        out[i] = place(cells_[i], uniforms[2 * i], uniforms[2 * i + 1], weight);
    }
}

double Footprint::variance_over_fixed() const {
    if (cells_.size() < 2) return 1.0;  // a lone sample on the axis has no variance to scale
    std::vector<SubRay> nodes(cells_.size());
    fixed(nodes);
    double sum = 0.0, sum2 = 0.0;
    for (const SubRay& s : nodes) {
        sum += s.offset_x_rad;
        sum2 += s.offset_x_rad * s.offset_x_rad;
    }
    const double n = static_cast<double>(nodes.size());
    // E[r^2] of the truncated Gaussian, F(r) = 1 - exp(-u), u = 2 r^2 / w^2 up to U:
    // (w^2 / 2) (1 - e^-U (1 + U)) / (1 - e^-U); each axis holds half of it.
    const double U = 2.0 * (max_radius_rad_ / waist_rad_) * (max_radius_rad_ / waist_rad_);
    const double mean_r2 = 0.5 * waist_rad_ * waist_rad_ * (1.0 - std::exp(-U) * (1.0 + U)) / captured_;
    return 0.5 * mean_r2 / (sum2 / n - (sum / n) * (sum / n));
}

std::optional<FootprintRect> Footprint::clip(const FootprintRect& rect) const {
    const FootprintRect r{std::max(rect.x_lo, -max_radius_rad_), std::min(rect.x_hi, max_radius_rad_),
                          std::max(rect.y_lo, -max_radius_rad_), std::min(rect.y_hi, max_radius_rad_)};
    if (!(r.x_lo < r.x_hi) || !(r.y_lo < r.y_hi)) return std::nullopt;
    return r;
}

bool Footprint::contains(const FootprintRect& rect, double x_rad, double y_rad) const {
    return x_rad >= rect.x_lo && x_rad <= rect.x_hi && y_rad >= rect.y_lo && y_rad <= rect.y_hi;
}

FootprintRect Footprint::square() const { return {-max_radius_rad_, max_radius_rad_, -max_radius_rad_, max_radius_rad_}; }

double Footprint::axis_cdf(double offset_rad) const { return normal_cdf(offset_rad / (0.5 * waist_rad_)); }

double Footprint::axis_offset(double cdf) const { return 0.5 * waist_rad_ * inverse_normal_cdf(cdf); }

}  // namespace ladarsim::sensor_model
