#include "ladarsim/sensor_model/footprint/edge_profile.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <Eigen/Cholesky>

namespace ladarsim::sensor_model {
namespace {

/// The samples must spread over at least this fraction of the footprint's radius across every
/// direction (the square root of their covariance's smaller eigenvalue) for a plane to be fitted.
constexpr double kMinSpan = 0.1;
/// Lines of constant range (a midpoint rule along the gradient) across the footprint: the most slices.
constexpr int kLines = 128;
/// A slice is at most 1 / kMinSlices of the footprint deep.
constexpr int kMinSlices = 8;
/// Lines holding this fraction of the side's densest line's mass and more are sliced finely.
constexpr double kDense = 0.5;

}  // namespace

std::optional<RangePlane> fit_range_plane(std::span<const RangeSample> samples, double max_offset_rad, double tolerance_m) {
    if (samples.size() < 4) return std::nullopt;
    // One pass of sums, in units of the truncation radius (range = c0 + c1 u + c2 v): the normal
    // equations, the samples' spread in offset, and the residual from the same sums.
    const double r = max_offset_rad;
    const double reference = samples.front().range_m;  // ranges relative to it: no cancellation below
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    double range2 = 0.0;
    for (const RangeSample& s : samples) {
        const Eigen::Vector3d row(1.0, s.offset.x() / r, s.offset.y() / r);
        normal.selfadjointView<Eigen::Lower>().rankUpdate(row);
        rhs += row * (s.range_m - reference);
        range2 += (s.range_m - reference) * (s.range_m - reference);
    }
    normal = normal.selfadjointView<Eigen::Lower>();
    const double n = normal(0, 0);
    // The smaller eigenvalue of the offsets' covariance (a 2 x 2 closed form).
    const double xx = normal(1, 1) / n - std::pow(normal(1, 0) / n, 2), yy = normal(2, 2) / n - std::pow(normal(2, 0) / n, 2);
    const double xy = normal(2, 1) / n - normal(1, 0) / n * normal(2, 0) / n;
    const double smaller = 0.5 * (xx + yy) - std::sqrt(0.25 * (xx - yy) * (xx - yy) + xy * xy);
    if (!(smaller >= kMinSpan * kMinSpan)) return std::nullopt;
    const Eigen::Vector3d c = normal.ldlt().solve(rhs);
    // Least squares: the residual sum of squares is sum r^2 - c . (A^T r).
    const double residual2 = std::max(0.0, range2 - c.dot(rhs));
    if (!(std::sqrt(residual2 / n) <= tolerance_m)) return std::nullopt;
    return RangePlane{reference + c(0), Eigen::Vector2d(c(1), c(2)) / r};
}

bool range_profile(const RangePlane& plane, const ChordSide& side, double max_offset_rad, double sigma_rad, double resolution_m,
                   std::vector<RangeSlice>& out) {
    const double r = max_offset_rad;
    const Eigen::Vector2d gradient = plane.per_rad * r;  // per truncation radius
    const double slope = gradient.norm();
    if (!(slope > 0.0)) return false;
    // Coordinates p along the gradient and q across it (in truncation radii); the side is
    // a p + b q > d (beyond). A fixed rule of kLines lines of constant p: the Gaussian along p and
    // its mass across the whole line are tabulated once.
    const Eigen::Vector2d along = gradient / slope, across(-along.y(), along.x());
    const double a = side.normal.dot(along), b = side.normal.dot(across), d = side.distance / r;
    const double s = sigma_rad / r, to_z = 1.0 / (s * std::numbers::sqrt2);
    const double dp = 2.0 / kLines;
    thread_local double tabulated_s = -1.0;
    thread_local std::array<double, kLines> density, half_line, whole_line;
    if (s != tabulated_s) {
        for (int j = 0; j < kLines; ++j) {
            const auto k = static_cast<std::size_t>(j);
            const double p = -1.0 + (j + 0.5) * dp;
            density[k] = std::exp(-0.5 * p * p / (s * s));
            half_line[k] = std::sqrt(1.0 - p * p);
            whole_line[k] = std::erf(half_line[k] * to_z);
        }
        tabulated_s = s;
    }
    // Each line's mass on the side, and the middle of its part there.
    std::array<double, kLines> mass, middle;
    double total = 0.0, densest = 0.0;
    for (int j = 0; j < kLines; ++j) {
        const auto k = static_cast<std::size_t>(j);
        mass[k] = 0.0;
        const double p = -1.0 + (j + 0.5) * dp;
        const double half = half_line[k];
        double lo = -half, hi = half;
        if (std::abs(b) < 1e-12) {
            if ((a * p > d) != side.beyond) continue;
        } else {
            const double t = (d - a * p) / b;  // where the chord crosses this line
            if ((b > 0.0) == side.beyond)
                lo = std::max(lo, t);
            else
                hi = std::min(hi, t);
        }
        if (!(hi > lo)) continue;
        // The line's mass between lo and hi, erf(half) the whole line's: the chord cuts it at one
        // end at most.
        const double across = lo > -half ? 0.5 * (whole_line[k] - std::erf(lo * to_z))
                              : hi < half ? 0.5 * (std::erf(hi * to_z) + whole_line[k])
                                          : whole_line[k];
        mass[k] = density[k] * across;
        middle[k] = 0.5 * (lo + hi);
        total += mass[k];
        densest = std::max(densest, mass[k]);
    }
    if (!(total > 0.0)) return false;
    // Lines grouped into slices `resolution_m` deep where the side is dense (half its densest
    // line's mass and more); in its tails, slices holding as much mass as a dense one
    // (deeper: fewer echoes), but no deeper than an eighth of the footprint's depth. (Growing the
    // slices from the densest line on blurred the peak beside it: gather_surfaces stretches each
    // echo half-way to its neighbours.)
    const double line_depth = slope * dp;
    const int fine_lines = std::clamp(static_cast<int>(std::floor(resolution_m / line_depth)), 1, kLines / kMinSlices);
    const double dense = kDense * densest, slice_mass = densest * fine_lines;
    auto is_dense = [&](int j) { return mass[static_cast<std::size_t>(j)] >= dense; };
    for (int j = 0; j < kLines;) {
        if (mass[static_cast<std::size_t>(j)] == 0.0) {
            ++j;
            continue;
        }
        double m = 0.0, p_sum = 0.0, p2_sum = 0.0, q_sum = 0.0;
        const int start = j;
        const bool fine = is_dense(j);
        const int most = fine ? fine_lines : kLines / kMinSlices;
        for (; j < kLines && j - start < most && mass[static_cast<std::size_t>(j)] > 0.0; ++j) {
            if (!fine && (m >= slice_mass || is_dense(j))) break;
            const auto k = static_cast<std::size_t>(j);
            const double p = -1.0 + (j + 0.5) * dp;
            m += mass[k];
            p_sum += mass[k] * p;
            p2_sum += mass[k] * p * p;
            q_sum += mass[k] * middle[k];
        }
        const double p = p_sum / m, q = q_sum / m;
        const double variance = std::max(0.0, p2_sum / m - p * p) + dp * dp / 12.0;  // the lines' own depth too
        out.push_back({(p * along + q * across) * r, plane.at_axis_m + slope * p, m / total, slope * std::sqrt(variance)});
    }
    return true;
}

}  // namespace ladarsim::sensor_model
