#pragma once
// One sub-ray of a lattice shared by the footprints that overlap it (TargetLattice).
#include <cstdint>
#include <optional>

#include <Eigen/Core>

#include "ladarsim/raytrace/traced_scene.h"

namespace ladarsim::sensor_model {

/// Where a shared sub-ray points and what it met, with the echo it would bring back carrying the
/// whole beam (a beam taking it scales that by its share).
struct LatticeSubRay {
    Eigen::Vector3d direction_world = Eigen::Vector3d::Zero();
    Eigen::Vector3d point_world = Eigen::Vector3d::Zero();
    Eigen::Vector3f normal_world = Eigen::Vector3f::Zero();
    double range_m = 0.0;
    double unit_echo_j = 0.0;
    std::uint32_t object_id = 0;
    bool hit = false;

    /// Fills what it met from its traced `h` (leaving `origin_world`); `unit_echo_j(hit)` is asked
    /// only when it met something.
    template <class UnitEcho>
    void met(const std::optional<raytrace::Hit>& h, const Eigen::Vector3d& origin_world, UnitEcho&& unit_echo) {
        hit = h.has_value();
        if (!hit) return;
        range_m = h->range_m;
        object_id = h->object_id;
        point_world = origin_world + h->range_m * direction_world;
        normal_world = h->normal_world;
        unit_echo_j = unit_echo(*h);
    }
};

}  // namespace ladarsim::sensor_model
