// Beam directions from gimbal pointing and raster offsets, against spherical-angle closed forms.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include <Eigen/LU>

#include "ladarsim/sensor_model/sensor/beam_geometry.h"
#include "ladarsim/sensor_model/sensor/gimbal.h"
#include "ladarsim/sensor_model/sensor/sensor.h"

using namespace ladarsim::sensor_model;

namespace {
Eigen::Vector3d spherical(double az, double el) {
    return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}
}  // namespace

TEST_CASE("beam axis points where the gimbal and galvo angles say", "[beam_geometry]") {
    CHECK((sensor_from_beam({}, 0.0, 0.0) - Eigen::Matrix3d::Identity()).norm() < 1e-15);
    for (double az : {-2.0, -0.3, 0.0, 0.7, 3.0}) {
        for (double el : {-0.5, 0.0, 0.2, 1.2}) {
            const Eigen::Vector3d axis = sensor_from_beam({az, el}, 0.0, 0.0).col(0);
            CHECK((axis - spherical(az, el)).norm() < 1e-14);
            const GimbalPointing back = pointing_towards(axis);
            CHECK(back.az_rad == Approx(az).margin(1e-14));
            CHECK(back.el_rad == Approx(el).margin(1e-14));
        }
    }
    // With the gimbal level, a galvo offset is a plain azimuth/elevation.
    const Eigen::Vector3d d = sensor_from_beam({0.0, 0.0}, 0.004, -0.003).col(0);
    CHECK((d - spherical(0.004, -0.003)).norm() < 1e-15);
    // The beam's own y and z axes (footprint offsets) stay orthonormal with the axis.
    const Eigen::Matrix3d m = sensor_from_beam({0.4, 0.3}, 0.004, -0.003);
    CHECK((m.transpose() * m - Eigen::Matrix3d::Identity()).norm() < 1e-14);
    CHECK(m.determinant() == Approx(1.0));
}

TEST_CASE("gimbal slews at its rate limit and stops at its limits", "[gimbal]") {
    const Sensor c = sensor_preset("paper_ladar");  // 16 deg/s, +-175 deg azimuth, -30..90 deg elevation
    const double deg = std::numbers::pi / 180.0;
    Gimbal g(c.gimbal, {});
    g.slew_towards({10 * deg, -2 * deg}, 0.05);  // one 20 Hz frame: at most 0.8 deg per axis
    CHECK(g.pointing().az_rad == Approx(0.8 * deg));
    CHECK(g.pointing().el_rad == Approx(-0.8 * deg));
    for (int i = 0; i < 20; ++i) g.slew_towards({10 * deg, -2 * deg}, 0.05);
    CHECK(g.pointing().az_rad == Approx(10 * deg));
    CHECK(g.pointing().el_rad == Approx(-2 * deg));
    Gimbal far(c.gimbal, {179 * deg, -80 * deg});
    CHECK(far.pointing().az_rad == Approx(175 * deg));
    CHECK(far.pointing().el_rad == Approx(-30 * deg));
}
