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

std::optional<CurvedPatch> fit_curved_patch(std::span<const SurfaceSample> samples, std::span<const PatchNode> nodes,
                                            double r_max_rad, double range_tolerance_m) {
    if (samples.size() < 6 || nodes.empty()) return std::nullopt;
    // One smooth surface: the range a quadratic of the offsets, every sample near it.
    Eigen::Matrix<double, 6, 6> normal = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
    for (const SurfaceSample& s : samples) {
        const Basis b = basis(s.x_rad, s.y_rad, r_max_rad);
        normal.selfadjointView<Eigen::Lower>().rankUpdate(b, s.irradiance);
        rhs += s.irradiance * s.range_m * b;
    }
    normal = normal.selfadjointView<Eigen::Lower>();
    // Scaled to a unit diagonal, so that the pivots measure how well each direction is determined.
    const Basis scale = normal.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
    const Eigen::Matrix<double, 6, 6> scaled = scale.asDiagonal() * normal * scale.asDiagonal();
    const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(scaled);
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > kMinPivot)) return std::nullopt;
    const Eigen::Matrix<double, 6, 1> coefficients = scale.asDiagonal() * ldlt.solve(scale.asDiagonal() * rhs);
    for (const SurfaceSample& s : samples)
        if (std::abs(s.range_m - basis(s.x_rad, s.y_rad, r_max_rad).dot(coefficients)) > range_tolerance_m) return std::nullopt;

    // The samples by lines of equal elevation offset (the raster's), each by azimuth offset.
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
    // A line's sample nearest a node in azimuth.
    auto nearest = [&](const std::pair<std::size_t, std::size_t>& line, double x) -> const SurfaceSample& {
        const auto first = sorted.begin() + static_cast<std::ptrdiff_t>(line.first), end = sorted.begin() + static_cast<std::ptrdiff_t>(line.second);
        const auto right = std::upper_bound(first, end, x, [](double v, const SurfaceSample& q) { return v < q.x_rad; });
        if (right == first) return *first;
        if (right == end || x - (right - 1)->x_rad <= right->x_rad - x) return *(right - 1);
        return *right;
    };
    // Range along `d` to the plane of the facet `s` met.
    auto range_on = [](const SurfaceSample& s, const Eigen::Vector3d& d) {
        const double nd = s.normal.dot(d);
        return std::abs(nd) > 1e-9 ? s.range_m * s.normal.dot(s.direction) / nd : -1.0;
    };
    double e_sum = 0.0, er_sum = 0.0, er2_sum = 0.0;
    for (const PatchNode& n : nodes) {
        const auto above = std::upper_bound(lines.begin(), lines.end(), n.y_rad,
                                            [&](double v, const std::pair<std::size_t, std::size_t>& l) { return v < sorted[l.first].y_rad; });
        const SurfaceSample* facet = nullptr;
        double range = -1.0;
        if (above == lines.begin() || above == lines.end()) {
            facet = &nearest(above == lines.begin() ? *above : *(above - 1), n.x_rad);
            range = range_on(*facet, n.direction);
        } else {
            const SurfaceSample &a = nearest(*(above - 1), n.x_rad), &b = nearest(*above, n.x_rad);
            const double ra = range_on(a, n.direction), rb = range_on(b, n.direction);
            // Folded towards the sensor where b's plane lies behind a's own point (and a's behind
            // b's): the surface is then the nearer of the two planes; folded away, the farther.
            const bool towards = range_on(b, a.direction) >= a.range_m;
            const bool nearer = towards ? ra <= rb : ra >= rb;
            facet = nearer ? &a : &b;
            range = nearer ? ra : rb;
        }
        if (!(range > 0.0)) return std::nullopt;
        const double seen = facet->reflectance * std::abs(facet->normal.dot(n.direction)) / (range * range);
        e_sum += seen;
        er_sum += seen * range;
        er2_sum += seen * range * range;
    }
    if (!(e_sum > 0.0)) return std::nullopt;
    const double range = er_sum / e_sum;
    return CurvedPatch{range, std::sqrt(std::max(0.0, er2_sum / e_sum - range * range)), e_sum / static_cast<double>(nodes.size())};
}

}  // namespace ladarsim::sensor_model
