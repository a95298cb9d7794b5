#include "map_discs.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace ladarsim::sensor_model {

namespace {

constexpr std::uint32_t kLeafDiscs = 8;

/// Whether a sphere may meet the cone: its lateral distance from the axis within the cone's
/// radius at its far side plus its own radius (conservative for cones of a few milliradians).
bool sphere_in_cone(const Eigen::Vector3d& centre, double radius, const Eigen::Vector3d& axis, double tan_half, double max_range_m) {
    const double along = centre.dot(axis);
    if (along < -radius || along > max_range_m + radius) return false;
    const double lateral2 = (centre - along * axis).squaredNorm();
    const double reach = std::max(0.0, along + radius) * tan_half + radius * (1.0 + tan_half);
    return lateral2 <= reach * reach;
}

}  // namespace

MapDiscs::MapDiscs(const scene::BackgroundMap& map, const Eigen::Vector3d& origin_world) {
    const std::size_t n = map.points_world.size();
    centre_.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        centre_.push_back(map.points_world[i] - origin_world);
        normal_.push_back(map.normals[i].cast<double>().normalized());
        radius_.push_back(map.radii_m[i]);
        reflectance_.push_back(map.reflectance[i]);
        order_.push_back(static_cast<std::uint32_t>(i));
    }
    if (n > 0) build(0, static_cast<std::uint32_t>(n));
}

std::uint32_t MapDiscs::build(std::uint32_t begin, std::uint32_t end) {
    Eigen::AlignedBox3d box, centres;
    for (std::uint32_t k = begin; k < end; ++k) {
        const std::uint32_t i = order_[k];
        box.extend(centre_[i] - Eigen::Vector3d::Constant(radius_[i]));
        box.extend(centre_[i] + Eigen::Vector3d::Constant(radius_[i]));
        centres.extend(centre_[i]);
    }
    const auto index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back({box.center(), 0.5 * box.diagonal().norm(), begin, end - begin});
    if (end - begin <= kLeafDiscs) return index;
    // Split at the median along the centres' longest side.
    int axis = 0;
    centres.diagonal().maxCoeff(&axis);
    const std::uint32_t middle = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                     [&](std::uint32_t a, std::uint32_t b) { return centre_[a][axis] < centre_[b][axis]; });
    build(begin, middle);
    const std::uint32_t second = build(middle, end);
    nodes_[index].first = second;
    nodes_[index].count = 0;
    return index;
}

void MapDiscs::in_cone(const Eigen::Vector3d& axis, double tan_half, double max_range_m, std::vector<std::uint32_t>& out) const {
    out.clear();
    if (nodes_.empty()) return;
    std::uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes_[stack[--top]];
        if (!sphere_in_cone(node.centre, node.radius, axis, tan_half, max_range_m)) continue;
        if (node.count == 0) {
            const auto self = static_cast<std::uint32_t>(&node - nodes_.data());
            stack[top++] = node.first;
            stack[top++] = self + 1;
            continue;
        }
        for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
            const std::uint32_t i = order_[k];
            if (sphere_in_cone(centre_[i], radius_[i], axis, tan_half, max_range_m)) out.push_back(i);
        }
    }
}

}  // namespace ladarsim::sensor_model
