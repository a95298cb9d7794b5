#pragma once
// One beam as the footprint integration sees it: where it points and when, the probes traced
// ahead for it, and what it met before the receiver.
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "ladarsim/raytrace/traced_scene.h"
#include "ladarsim/sensor_model/signal/beam_receiver.h"
#include "ladarsim/sensor_model/signal/surface_grouping.h"

namespace ladarsim::sensor_model {

/// Where one beam points and when it fires.
struct BeamAim {
    Eigen::Matrix3d world_from_beam;  ///< x along the beam, y left, z up
    Eigen::Vector3d origin_world;     ///< where it leaves: the sensor at its time
    double time_s;
    std::uint32_t cell;               ///< raster cell index: keys the beam's random draws
};

/// A probe ray's hit, with what the plane test asks of it found once for every beam whose
/// footprint the probe falls in (some 25).
struct ProbeHit {
    std::optional<raytrace::Hit> hit;
    Eigen::Vector3d point_world = Eigen::Vector3d::Zero();  ///< origin + range_m * direction
    double seen = 0.0;  ///< reflectance * cos_incidence / range_m^2: the energy it saw, but constants
    /// Fills the fields above from `hit` of a probe leaving `origin` along `direction`.
    void set(const std::optional<raytrace::Hit>& h, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) {
        hit = h;
        if (!h) return;
        point_world = origin + h->range_m * direction;
        seen = h->reflectance * h->cos_incidence / (h->range_m * h->range_m);
    }
};

/// A ray traced ahead for a beam: the beam's own axis, a neighbouring beam's axis that falls
/// inside its footprint, or an extra ray where the raster leaves the footprint uncovered; or a
/// sentinel, a neighbouring axis just beyond the footprint's truncation.
struct Probe {
    double x_rad, y_rad;  ///< offset from the beam axis, in footprint coordinates
    double irradiance;    ///< the beam's relative irradiance there, exp(-2 r^2 / w^2)
    Eigen::Vector3d direction_world;
    const ProbeHit* hit;
};

/// What one beam met, before the receiver.
struct BeamEchoes {
    std::vector<SurfaceEcho> surface;
    std::vector<BeamSurface> volume;
    int rays = 0;  ///< traced for this beam after its probes (a measure of cost)
};

}  // namespace ladarsim::sensor_model
