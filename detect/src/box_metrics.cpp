#include "ladarsim/detect/box_metrics.h"

#include <algorithm>
#include <cmath>

namespace ladarsim::detect {

double centre_distance_m(const OrientedBox& a, const OrientedBox& b) {
    return (a.centre - b.centre).norm();
}

double axis_aligned_iou(const OrientedBox& a, const OrientedBox& b) {
    const Eigen::Vector3d a_lo = a.centre - 0.5 * a.size, a_hi = a.centre + 0.5 * a.size;
    const Eigen::Vector3d b_lo = b.centre - 0.5 * b.size, b_hi = b.centre + 0.5 * b.size;
    double intersection = 1.0;
    for (int i = 0; i < 3; ++i) {
        intersection *= std::max(0.0, std::min(a_hi[i], b_hi[i]) - std::max(a_lo[i], b_lo[i]));
    }
    const double volume_a = a.size.prod(), volume_b = b.size.prod();
    const double union_volume = volume_a + volume_b - intersection;
    return union_volume > 0.0 && volume_a > 0.0 && volume_b > 0.0 ? intersection / union_volume : 0.0;
}

double bev_iou(const OrientedBox& a, const OrientedBox& b) {
    double intersection = 1.0;
    for (int i = 0; i < 2; ++i) {
        const double lo = std::max(a.centre[i] - 0.5 * a.size[i], b.centre[i] - 0.5 * b.size[i]);
        const double hi = std::min(a.centre[i] + 0.5 * a.size[i], b.centre[i] + 0.5 * b.size[i]);
        intersection *= std::max(0.0, hi - lo);
    }
    const double area_a = a.size.x() * a.size.y(), area_b = b.size.x() * b.size.y();
    const double union_area = area_a + area_b - intersection;
    return area_a > 0.0 && area_b > 0.0 && union_area > 0.0 ? intersection / union_area : 0.0;
}

OrientedBox sensor_aware_box(const OrientedBox& points_box, double footprint_width_rad, const Eigen::Vector3d& prior_size) {
    OrientedBox out = points_box;
    const double range = points_box.centre.norm();
    if (!(range > 0.0)) return out;
    const Eigen::Vector3d line_of_sight = points_box.centre / range;
    const double width = footprint_width_rad * range;
    for (int i = 0; i < 3; ++i) {
        // A disc of that width across the line of sight, seen along axis i.
        const double spread = width * std::sqrt(std::max(0.0, 1.0 - line_of_sight[i] * line_of_sight[i]));
        out.size[i] = std::max(points_box.size[i] - spread, prior_size[i]);
    }
    return out;
}

}  // namespace ladarsim::detect
