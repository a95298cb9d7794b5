#include "ladarsim/sensor_model/curved_patch.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

namespace ladarsim::sensor_model {

namespace {

using Basis = Eigen::Matrix<double, 6, 1>;

Basis basis(double x_rad, double y_rad, double r_max_rad) {
    const double u = x_rad / r_max_rad, v = y_rad / r_max_rad;
    return (Basis() << 1.0, u, v, u * u, u * v, v * v).finished();
}

/// A pivot of the normalised normal equations below this: the samples do not fix that direction
/// of the quadratic (three samples on a line leave its curvature across the line free).
constexpr double kMinPivot = 1e-6;

}  // namespace

std::optional<CurvedPatch> fit_curved_patch(std::span<const SurfaceSample> samples, std::span<const Eigen::Vector2d> nodes,
                                            double r_max_rad, double range_tolerance_m) {
    if (samples.size() < 6 || nodes.empty()) return std::nullopt;
    Eigen::Matrix<double, 6, 6> normal = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
    double g_sum = 0.0;
    for (const SurfaceSample& s : samples) {
        const Basis b = basis(s.x_rad, s.y_rad, r_max_rad);
        normal.selfadjointView<Eigen::Lower>().rankUpdate(b, s.irradiance);
        rhs += s.irradiance * s.range_m * b;
        g_sum += s.irradiance;
    }
    if (!(g_sum > 0.0)) return std::nullopt;
    normal = normal.selfadjointView<Eigen::Lower>();
    // Scaled to a unit diagonal, so that the pivots measure how well each direction is determined.
    const Basis scale = normal.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
    const Eigen::Matrix<double, 6, 6> scaled = scale.asDiagonal() * normal * scale.asDiagonal();
    const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(scaled);
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > kMinPivot)) return std::nullopt;
    const Eigen::Matrix<double, 6, 1> coefficients = scale.asDiagonal() * ldlt.solve(scale.asDiagonal() * rhs);
    for (const SurfaceSample& s : samples)
        if (std::abs(s.range_m - basis(s.x_rad, s.y_rad, r_max_rad).dot(coefficients)) > range_tolerance_m) return std::nullopt;
    // The echo between the samples: linear between neighbours along a line of samples, and between
    // lines. Where it steps (a change of facet, so of cos(incidence)) somewhere between two samples,
    // the step's place unknown, linear interpolation is its expectation; a quadratic through three
    // lines of samples over- or undershoots it (the bench's horizon: the terrain's energy 1.24 %
    // high against 4096 sub-rays, linear 1.01 %, refined cells 1.18 %).
    thread_local std::vector<SurfaceSample> sorted;
    sorted.assign(samples.begin(), samples.end());
    std::sort(sorted.begin(), sorted.end(), [](const SurfaceSample& a, const SurfaceSample& b) {
        return a.y_rad != b.y_rad ? a.y_rad < b.y_rad : a.x_rad < b.x_rad;
    });
    const double same_line = 1e-6 * r_max_rad;
    thread_local std::vector<std::pair<std::size_t, std::size_t>> lines;  // [first, end) in `sorted`
    lines.clear();
    for (std::size_t k = 0; k < sorted.size();) {
        std::size_t end = k + 1;
        while (end < sorted.size() && std::abs(sorted[end].y_rad - sorted[k].y_rad) <= same_line) ++end;
        std::sort(sorted.begin() + static_cast<std::ptrdiff_t>(k), sorted.begin() + static_cast<std::ptrdiff_t>(end),
                  [](const SurfaceSample& a, const SurfaceSample& b) { return a.x_rad < b.x_rad; });
        lines.emplace_back(k, end);
        k = end;
    }
    auto along = [&](const std::pair<std::size_t, std::size_t>& line, double x) {
        const auto first = sorted.begin() + static_cast<std::ptrdiff_t>(line.first), end = sorted.begin() + static_cast<std::ptrdiff_t>(line.second);
        const auto right = std::upper_bound(first, end, x, [](double v, const SurfaceSample& q) { return v < q.x_rad; });
        if (right == first) return first->seen;
        if (right == end) return (end - 1)->seen;
        const auto left = right - 1;
        const double t = (x - left->x_rad) / (right->x_rad - left->x_rad);
        return left->seen + t * (right->seen - left->seen);
    };
    auto seen_at = [&](double x, double y) {
        const auto above = std::upper_bound(lines.begin(), lines.end(), y,
                                            [&](double v, const std::pair<std::size_t, std::size_t>& l) { return v < sorted[l.first].y_rad; });
        if (above == lines.begin()) return along(*above, x);
        if (above == lines.end()) return along(*(above - 1), x);
        const auto below = above - 1;
        const double y0 = sorted[below->first].y_rad, y1 = sorted[above->first].y_rad;
        const double t = (y - y0) / (y1 - y0);
        return (1.0 - t) * along(*below, x) + t * along(*above, x);
    };
    double e_sum = 0.0, er_sum = 0.0, er2_sum = 0.0;
    for (const Eigen::Vector2d& n : nodes) {
        const double range = basis(n.x(), n.y(), r_max_rad).dot(coefficients), seen = seen_at(n.x(), n.y());
        if (!(range > 0.0) || !(seen > 0.0)) return std::nullopt;
        e_sum += seen;
        er_sum += seen * range;
        er2_sum += seen * range * range;
    }
    const double mean_seen = e_sum / static_cast<double>(nodes.size());
    const double range = er_sum / e_sum;
    return CurvedPatch{range, std::sqrt(std::max(0.0, er2_sum / e_sum - range * range)), mean_seen};
}

}  // namespace ladarsim::sensor_model
