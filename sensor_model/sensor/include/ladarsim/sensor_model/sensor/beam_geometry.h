#pragma once
#include <Eigen/Core>

#include "ladarsim/sensor_model/sensor/gimbal.h"

namespace ladarsim::sensor_model {

/// Rotation taking beam coordinates (x along the beam, y to its left, z up) to the sensor frame:
///   sensor_from_beam = Rz(gimbal az) * Ry(-gimbal el) * Rz(az offset) * Ry(-el offset),
/// i.e. the gimbal turns the raster, and the galvo turns the beam inside the raster.
/// (A rotation about +y by +a tips +x down, hence the minus signs for elevation.)
Eigen::Matrix3d sensor_from_beam(GimbalPointing pointing, double az_offset_rad, double el_offset_rad);

/// Azimuth and elevation of a direction in the sensor frame (zero for a zero vector).
GimbalPointing pointing_towards(const Eigen::Vector3d& direction_sensor);

/// The unit direction at an azimuth and elevation: the inverse of pointing_towards.
Eigen::Vector3d direction_towards(GimbalPointing angles);

}  // namespace ladarsim::sensor_model
