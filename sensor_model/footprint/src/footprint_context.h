#pragma once
// What every strategy of one footprint integrator shares: the scene as traced, the beam's shape,
// the receiver's radiometry, and the figures the settings give, found once.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "ladarsim/raytrace/traced_scene.h"
#include "ladarsim/sensor_model/footprint/beam.h"
#include "ladarsim/sensor_model/footprint/beam_shape.h"
#include "ladarsim/sensor_model/footprint/footprint_settings.h"
#include "ladarsim/sensor_model/sensor/sensor.h"
#include "ladarsim/sensor_model/signal/echo_radiometry.h"

namespace ladarsim::sensor_model {

/// Directions integrating a plane patch (no rays): an adaptive footprint's equal-energy cells.
inline constexpr int kPlaneQuadrature = 16;

/// Depths a sub-ray in a medium takes for where it scatters (add_volume_echoes): they cost no ray,
/// and with one a sub-ray a cloud's return was placed by the few dozen sub-rays of a footprint. The
/// bench's cloud edge, first returns against 4096 sub-rays' (mean / median) and beams/s: 1 depth
/// 167 / 125 mm, 146 k; 4: 42 / 32 mm, 141 k; 8: 21 / 17 mm, 135 k; 16: 11 / 9 mm, 131 k; dataset 3
/// (a cloud most beams cross) renders in 15.5, 17.7 and 19.8 s at 1, 8 and 16.
inline constexpr int kFreePaths = 8;

struct FootprintContext {
    FootprintContext(const FootprintSettings& settings, const Sensor& sensor, const raytrace::TracedScene& traced,
                     const EchoRadiometry& radiometry);

    /// A ray leaving the sensor at the beam's time towards footprint offset (x, y).
    raytrace::Ray ray(const BeamAim& aim, double x_rad, double y_rad) const {
        raytrace::Ray r;
        r.origin_world = aim.origin_world;
        r.direction = aim.world_from_beam * shape.in_beam(x_rad, y_rad);
        r.time_s = aim.time_s;
        r.max_range_m = max_range_m;
        return r;
    }
    /// Echo energy of a sub-ray carrying `weight` of the beam (radiometry.echo_energy_j).
    double echo_energy_j(double weight, double reflectance, double cos_incidence, double range_m, double fog) const {
        return radiometry.echo_energy_j(weight, reflectance, cos_incidence, range_m, fog);
    }

    FootprintSettings settings;
    const Sensor& sensor;
    const raytrace::TracedScene& traced;
    const EchoRadiometry& radiometry;
    bool adaptive;
    double max_range_m;
    double return_gap_m;
    /// A target outline's (and a map footprint's) sub-ray budget at this tolerance.
    std::size_t outline_samples;
    BeamShape shape;
    double small_object_rad;  ///< objects subtending less than this are sampled explicitly
    double pulse_sigma_m;     ///< the pulse's standard deviation, in range
    double threshold_j;       ///< radiometry.threshold_energy_j(0): an unstretched pulse's, found once
    int grid_base;            ///< cells along each axis of a bright lone target's grid (grid_base^2 ~ outline_samples)
    double aperture_radius2;  ///< r_a^2 of the range equation's view factor
};

}  // namespace ladarsim::sensor_model
