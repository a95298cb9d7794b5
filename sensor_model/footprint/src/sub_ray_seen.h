#pragma once
// What one sub-ray met, as the cell refinement and a straight edge compare it with others'.
#include <algorithm>
#include <cstdint>

#include <Eigen/Core>

#include "ladarsim/sensor_model/signal/surface_grouping.h"

namespace ladarsim::sensor_model {

/// Two sub-rays on one surface whose reflectances differ by more than this factor straddle a change
/// of material (a reflectance edge).
inline constexpr double kMaterialContrast = 2.0;

struct Seen {
    bool hit = false;
    /// Range, object, point and normal; energy_j per unit of beam share.
    SurfaceEcho echo{0.0, 0.0, 0.0, 0.0, 0, Eigen::Vector3d::Zero(), Eigen::Vector3f::Zero(), 0};
    std::uint64_t volumes = 0;   ///< which media it crossed (one bit per object id modulo 64)
    float reflectance = 0.0f;
    float cos_incidence = 1.0f;
};

/// Whether two sub-rays (or a probe and a sub-ray) can sit in one cell of a smooth integrand: both
/// met nothing, or both met one surface of one object, of reflectances within a factor of each
/// other (the echo itself changes smoothly with range and incidence across a surface).
inline bool agree(const Seen& a, const Seen& b, double gap_m) {
    if (a.volumes != b.volumes || a.hit != b.hit) return false;
    if (!a.hit) return true;
    if (a.echo.object_id != b.echo.object_id) return false;
    const bool a_first = a.echo.range_m <= b.echo.range_m;
    if (!same_surface(a_first ? a.echo : b.echo, a_first ? b.echo : a.echo, gap_m)) return false;
    const double lo = std::min(a.reflectance, b.reflectance), hi = std::max(a.reflectance, b.reflectance);
    return hi <= kMaterialContrast * lo;
}

}  // namespace ladarsim::sensor_model
