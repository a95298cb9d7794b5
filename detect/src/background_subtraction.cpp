#include "ladarsim/detect/background_subtraction.h"

#include <cmath>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <unordered_set>

namespace ladarsim::detect {

/// Voxels of side `resolution` holding a map point, dilated by one voxel in every direction.
struct BackgroundSubtractor::VoxelSet {
    std::unordered_set<std::uint64_t> near_map;
    double inverse_resolution = 1.0;

    std::array<std::int64_t, 3> voxel(const Eigen::Vector3f& p) const {
        return {static_cast<std::int64_t>(std::floor(p.x() * inverse_resolution)),
                static_cast<std::int64_t>(std::floor(p.y() * inverse_resolution)),
                static_cast<std::int64_t>(std::floor(p.z() * inverse_resolution))};
    }
    /// 21 bits per axis: +-1e6 voxels, +-1000 km at 1 m.
    static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
        constexpr std::int64_t kOffset = 1 << 20;
        constexpr std::uint64_t kMask = (1u << 21) - 1;
        return (static_cast<std::uint64_t>(x + kOffset) & kMask) << 42 | (static_cast<std::uint64_t>(y + kOffset) & kMask) << 21 |
               (static_cast<std::uint64_t>(z + kOffset) & kMask);
    }
};

BackgroundSubtractor::BackgroundSubtractor(const Points& map, double resolution_m, double range_tolerance_m)
    : resolution_(resolution_m), range_tolerance_(range_tolerance_m) {
    if (!(resolution_m > 0.0)) throw std::invalid_argument("background subtraction resolution must be positive");
    if (!(range_tolerance_m >= 0.0)) throw std::invalid_argument("background subtraction range tolerance must not be negative");
    voxels_ = std::make_unique<VoxelSet>();
    voxels_->inverse_resolution = 1.0 / resolution_m;
    std::unordered_set<std::uint64_t> occupied;
    for (const auto& p : map) {
        const auto v = voxels_->voxel(p);
        if (!occupied.insert(VoxelSet::key(v[0], v[1], v[2])).second) continue;
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) voxels_->near_map.insert(VoxelSet::key(v[0] + dx, v[1] + dy, v[2] + dz));
    }
}

BackgroundSubtractor::~BackgroundSubtractor() = default;

Points BackgroundSubtractor::subtract(const Points& frame) const {
    Points kept;
    auto near_map = [&](const Eigen::Vector3f& q) {
        const auto v = voxels_->voxel(q);
        return voxels_->near_map.contains(VoxelSet::key(v[0], v[1], v[2]));
    };
    // Steps along the line of sight of a voxel each (the dilated voxels leave no gap between them).
    const int steps = static_cast<int>(std::ceil(range_tolerance_ / resolution_));
    for (const auto& p : frame) {
        bool background = near_map(p);
        const float range = p.norm();
        if (!background && steps > 0 && range > 0.0f) {
            const Eigen::Vector3f step = p * static_cast<float>(range_tolerance_ / steps / range);
            for (int k = 1; k <= steps && !background; ++k) background = near_map(p + float(k) * step) || near_map(p - float(k) * step);
        }
        if (!background) kept.push_back(p);
    }
    return kept;
}

}  // namespace ladarsim::detect
