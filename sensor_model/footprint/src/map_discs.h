#pragma once
// The recorded map's discs as a beam's cone finds them: a bounding-volume hierarchy over their
// spheres, in coordinates relative to the sensor (docs/sensor.md, "Footprint and returns").
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "ladarsim/scene/scene.h"

namespace ladarsim::sensor_model {

class MapDiscs {
public:
    /// `origin_world`: where every ray leaves (the disc centres are kept relative to it).
    MapDiscs(const scene::BackgroundMap& map, const Eigen::Vector3d& origin_world);

    /// Appends to `out` (cleared first) every disc whose bounding sphere may meet the cone of apex
    /// the origin, unit axis `axis`, half-angle atan(`tan_half`), up to `max_range_m` (a superset:
    /// each leaf's box is tested by its sphere).
    void in_cone(const Eigen::Vector3d& axis, double tan_half, double max_range_m, std::vector<std::uint32_t>& out) const;

    const Eigen::Vector3d& centre(std::uint32_t i) const { return centre_[i]; }  ///< relative to the origin
    const Eigen::Vector3d& normal(std::uint32_t i) const { return normal_[i]; }
    double radius(std::uint32_t i) const { return radius_[i]; }
    double reflectance(std::uint32_t i) const { return reflectance_[i]; }
    std::size_t size() const { return centre_.size(); }

private:
    struct Node {
        Eigen::Vector3d centre;  ///< of its box
        double radius;           ///< half its box's diagonal
        std::uint32_t first;     ///< a leaf's first disc in order_, or an inner node's second child
        std::uint32_t count;     ///< discs of a leaf; 0 for an inner node (its first child follows it)
    };
    std::uint32_t build(std::uint32_t begin, std::uint32_t end);

    std::vector<Eigen::Vector3d> centre_, normal_;
    std::vector<double> radius_, reflectance_;
    std::vector<std::uint32_t> order_;
    std::vector<Node> nodes_;
};

}  // namespace ladarsim::sensor_model
