#include "ladarsim/detect/box_metrics.h"

#include <algorithm>

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

}  // namespace ladarsim::detect
