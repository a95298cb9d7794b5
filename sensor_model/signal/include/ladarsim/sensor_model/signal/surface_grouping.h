#pragma once
// The distinct surfaces along one beam, grouped from the echoes of its sub-rays (or patches) before
// the receiver sees them.
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include <Eigen/Core>

#include "ladarsim/sensor_model/signal/beam_receiver.h"

namespace ladarsim::sensor_model {

/// The echo of one sub-ray, or of a whole patch of one surface.
struct SurfaceEcho {
    double range_m;
    double weight;    ///< share of the beam's energy
    double energy_j;  ///< reaching the detector
    double spread_m;  ///< standard deviation of the range across a patch; 0 for a sub-ray
    std::uint32_t object_id;
    Eigen::Vector3d point_world;
    Eigen::Vector3f normal_world;
    std::uint32_t sample = 0;  ///< which sub-ray made it, for the integrator's bookkeeping
};

/// How far a continuous surface may bend away from a tangent plane, per metre along it: 5 deg
/// between the facets of a terrain or a hull still make one surface, however far apart the
/// sub-rays that sampled them.
inline const double kSurfaceBend = std::sin(5.0 * std::numbers::pi / 180.0);

/// Two echoes of one object, `a` the nearer, on one continuous surface: within `gap_m` in range,
/// or each within the gap (plus a bend of kSurfaceBend over their separation) of the other's
/// tangent plane. (Inline: the refinement compares every pair of neighbouring cells with it.)
inline bool same_surface(const SurfaceEcho& a, const SurfaceEcho& b, double gap_m) {
    if (b.range_m - a.range_m <= gap_m) return true;
    const Eigen::Vector3d d = b.point_world - a.point_world;
    const double allowed = gap_m + kSurfaceBend * d.norm();
    return std::abs(a.normal_world.cast<double>().dot(d)) <= allowed && std::abs(b.normal_world.cast<double>().dot(d)) <= allowed;
}

/// Groups echoes (sorted here by object and range) into the distinct surfaces along a beam, each
/// of one object. Two of its echoes, neighbours in range, are one surface when same_surface holds
/// (a surface seen at grazing incidence spans metres in range and would otherwise break into one
/// return per sub-ray). Each echo's pulse is stretched to reach half-way to its neighbours in
/// range, so that the result does not depend on how densely the surface was sampled. Echoes of
/// different objects are never one surface, however close: their pulses merge in the waveform,
/// which names a merged return after the object that sets its range. With `surface_of_echo`, also
/// which surface each echo (in the sorted order) went to.
std::vector<BeamSurface> gather_surfaces(std::vector<SurfaceEcho>& echoes, double gap_m,
                                         std::vector<std::uint32_t>* surface_of_echo = nullptr);
/// The same into `surfaces`, whose elements (and their echo lists) are reused.
void gather_surfaces(std::vector<SurfaceEcho>& echoes, double gap_m, std::vector<BeamSurface>& surfaces,
                     std::vector<std::uint32_t>* surface_of_echo = nullptr);

}  // namespace ladarsim::sensor_model
