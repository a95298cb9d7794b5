// A small target between two scan lines, on closed-form returns: each beam's echo follows the
// Gaussian beam's profile at the target's offset from the beam's axis.
#include <catch2/catch.hpp>

#include <cmath>

#include "ladarsim/core/units.h"
#include "ladarsim/detect/line_profile.h"
#include "ladarsim/detect/tracker.h"

using namespace ladarsim::detect;
using ladarsim::SensorGeometry;

namespace {

/// The paper's raster: 150 x 20 beams over 0.5 x 0.5 deg, 0.62 mrad beams (1/e^2 radius 0.31 mrad).
const SensorGeometry kPaperSensor{
    .beams_az = 150, .beams_el = 20, .field_az_deg = 0.5, .field_el_deg = 0.5, .divergence_mrad = 0.62};
constexpr double kPitchAz = 0.5 * ladarsim::kDeg / 150.0, kPitchEl = 0.5 * ladarsim::kDeg / 20.0;
constexpr double kRadius = 0.31e-3;

Eigen::Vector3f along(double range, double az, double el) {
    return (range * Eigen::Vector3d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el))).cast<float>();
}

/// The returns of a point target at (az_t, el_t): the 16 beams nearest it in azimuth on the lines
/// at elevations 0 and one pitch, each with the beam's irradiance at the target.
struct Returns {
    Points points;
    std::vector<float> intensity;
};
Returns point_target(double range, double az_t, double el_t) {
    Returns r;
    for (int row = 0; row < 2; ++row)
        for (int column = -8; column < 8; ++column) {
            const double az = column * kPitchAz, el = row * kPitchEl;
            const double off2 = (az - az_t) * (az - az_t) + (el - el_t) * (el - el_t);
            r.points.push_back(along(range, az, el));
            r.intensity.push_back(static_cast<float>(1000.0 * std::exp(-2.0 * off2 / (kRadius * kRadius))));
        }
    return r;
}

double elevation_of(const Eigen::Vector3d& p) { return std::atan2(p.z(), p.head<2>().norm()); }

}  // namespace

TEST_CASE("line profile: two lines' peak echoes give a target's elevation between them", "[detect][line_profile]") {
    const double el_t = 0.3 * kPitchEl;
    const Returns r = point_target(600.0, 0.2 * kPitchAz, el_t);
    const auto e = target_elevation_rad(r.points, r.intensity, kPitchEl, kRadius, 4.0);
    REQUIRE(e);
    CHECK(*e == Approx(el_t).margin(1e-8));
}

TEST_CASE("line profile: peaks closer than the trusted ratio, or one line, leave the midpoint", "[detect][line_profile]") {
    // 0.45 pitch above the lower line the peaks differ by exp(0.2 pitch^2 / radius^2) = 1.49.
    const Returns r = point_target(600.0, 0.0, 0.45 * kPitchEl);
    CHECK_FALSE(target_elevation_rad(r.points, r.intensity, kPitchEl, kRadius, 4.0));
    CHECK(target_elevation_rad(r.points, r.intensity, kPitchEl, kRadius, 1.0));
    const Points one_line(r.points.begin(), r.points.begin() + 16);
    const std::vector<float> its(r.intensity.begin(), r.intensity.begin() + 16);
    CHECK_FALSE(target_elevation_rad(one_line, its, kPitchEl, kRadius, 1.0));
}

TEST_CASE("line profile: the cued tracker's sensor-aware box sits at the target's height, not between the lines", "[detect][line_profile]") {
    const double range = 600.0, el_t = 0.3 * kPitchEl;  // 0.08 m above the lower line, 0.05 m below the midpoint
    const Returns r = point_target(range, 0.0, el_t);
    DetectorConfig config;
    config.lambda = 180.0;
    const Eigen::Vector3d cue = along(1.0, 0.0, el_t).cast<double>().normalized();
    TargetTracker with(config, kPaperSensor, {});
    const Detection d = with.process(0, 0.0, r.points, cue, r.intensity);
    REQUIRE(d.found);
    CHECK(std::abs(elevation_of(d.sensor_box.centre) - el_t) * range < 1e-3);
    // Without intensities the box stays between the lines: more than the 6 cm drone's height off.
    TargetTracker without(config, kPaperSensor, {});
    const Detection m = without.process(0, 0.0, r.points, cue);
    REQUIRE(m.found);
    CHECK(std::abs(elevation_of(m.sensor_box.centre) - el_t) * range > 0.04);
}
