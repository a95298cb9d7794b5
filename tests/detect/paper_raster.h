#pragma once
// The paper's raster for closed-form returns in detect/'s tests.
#include <cmath>

#include <Eigen/Core>

#include "ladarsim/core/units.h"
#include "ladarsim/dataset/manifest.h"

namespace paper_raster {

/// 150 x 20 beams over 0.5 x 0.5 deg, 0.62 mrad beams.
inline const ladarsim::SensorGeometry kPaperSensor{
    .beams_az = 150, .beams_el = 20, .field_az_deg = 0.5, .field_el_deg = 0.5, .divergence_mrad = 0.62};
/// Its beam pitches, radians.
constexpr double kPitchAz = 0.5 * ladarsim::kDeg / 150.0, kPitchEl = 0.5 * ladarsim::kDeg / 20.0;

/// The point at `range` along the beam at (az, el), sensor frame.
inline Eigen::Vector3f along(double range, double az, double el) {
    return (range * Eigen::Vector3d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el))).cast<float>();
}

}  // namespace paper_raster
