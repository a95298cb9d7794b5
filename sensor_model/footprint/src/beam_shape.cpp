#include "ladarsim/sensor_model/footprint/beam_shape.h"

#include <cmath>

namespace ladarsim::sensor_model {

Eigen::Vector3d BeamShape::in_beam(double x_rad, double y_rad) const {
    // tan(a) = a + a^3 / 3 + 2 a^5 / 15 + ...: below 0.01 rad the series' first two terms are exact
    // to 1e-9 relative, and cost a tenth of std::tan (footprints are milliradians).
    auto tangent = [](double a) { return std::abs(a) < 0.01 ? a + a * a * a / 3.0 : std::tan(a); };
    // The footprint is round in units of the azimuth divergence; elliptical beams stretch it in elevation.
    return Eigen::Vector3d(1.0, tangent(x_rad), tangent(y_rad * ellipticity_)).normalized();
}

}  // namespace ladarsim::sensor_model
