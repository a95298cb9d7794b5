#include "ladarsim/sensor_model/footprint/curved_patch_fit.h"

#include <algorithm>
#include <cmath>

namespace ladarsim::sensor_model {

namespace {

/// Samples on at least this many lines of the raster, so that the footprint's middle and both its
/// sides in elevation have facets of their own (a single line would be extrapolated across it).
constexpr std::size_t kMinLines = 3;
constexpr std::size_t kMinSamples = 6;

}  // namespace

std::optional<CurvedPatchFit> fit_curved_patch(std::span<const SurfaceSample> samples, std::span<const PatchNode> nodes,
                                            double r_max_rad, double coplanar_m) {
    if (samples.size() < kMinSamples || nodes.empty()) return std::nullopt;

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
    if (lines.size() < kMinLines) return std::nullopt;
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
            // Folded towards the sensor where b's plane lies behind a's own point and a's behind
            // b's: the surface is then the nearer of the two planes; folded away (each in front of
            // the other's point), the farther. One behind and one in front is no fold but a
            // jump in range: a nearer surface hiding part of a farther one.
            const double a_to_b = range_on(b, a.direction) - a.range_m, b_to_a = range_on(a, b.direction) - b.range_m;
            const double jump = std::max(coplanar_m, 0.5 * std::abs(a.range_m - b.range_m));
            if ((a_to_b > jump && b_to_a < -jump) || (a_to_b < -jump && b_to_a > jump)) return std::nullopt;
            const bool towards = a_to_b + b_to_a >= 0.0;
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
    return CurvedPatchFit{range, std::sqrt(std::max(0.0, er2_sum / e_sum - range * range)), e_sum / static_cast<double>(nodes.size())};
}

}  // namespace ladarsim::sensor_model
