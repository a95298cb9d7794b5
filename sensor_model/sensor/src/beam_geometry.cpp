#include "ladarsim/sensor_model/sensor/beam_geometry.h"

#include <cmath>

#include <Eigen/Geometry>

namespace ladarsim::sensor_model {

Eigen::Matrix3d sensor_from_beam(GimbalPointing pointing, double az_offset_rad, double el_offset_rad) {
    using Eigen::AngleAxisd;
    using Eigen::Vector3d;
    return (AngleAxisd(pointing.az_rad, Vector3d::UnitZ()) * AngleAxisd(-pointing.el_rad, Vector3d::UnitY()) *
            AngleAxisd(az_offset_rad, Vector3d::UnitZ()) * AngleAxisd(-el_offset_rad, Vector3d::UnitY()))
        .toRotationMatrix();
}

GimbalPointing pointing_towards(const Eigen::Vector3d& d) {
    if (d.isZero()) return {};
    return {std::atan2(d.y(), d.x()), std::atan2(d.z(), std::hypot(d.x(), d.y()))};
}

Eigen::Vector3d direction_towards(GimbalPointing a) {
    return {std::cos(a.az_rad) * std::cos(a.el_rad), std::sin(a.az_rad) * std::cos(a.el_rad), std::sin(a.el_rad)};
}

}  // namespace ladarsim::sensor_model
