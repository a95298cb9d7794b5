// A small target between two scan lines, on closed-form returns: each beam's echo follows the
// Gaussian beam's profile at the target's offset from the beam's axis.
#include <catch2/catch.hpp>

#include <cmath>

#include "ladarsim/core/units.h"
#include "ladarsim/detect/line_profile.h"
#include "ladarsim/detect/tracker.h"
#include "paper_raster.h"

using namespace ladarsim::detect;
using namespace paper_raster;

namespace {

/// The paper's beam: 1/e^2 intensity radius, half its 0.62 mrad divergence.
constexpr double kRadius = 0.31e-3;

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
    const auto pair = strongest_line_pair(r.points, r.intensity, kPitchEl);
    REQUIRE(pair);
    CHECK(pair->lower_rad == Approx(0.0).margin(1e-9));
    CHECK(pair->upper_rad == Approx(kPitchEl).epsilon(1e-6));
    CHECK(elevation_between(*pair, pair->log_ratio, kRadius) == Approx(el_t).margin(1e-8));
    // Returns on one line say nothing of where between lines the target is.
    const Points one_line(r.points.begin(), r.points.begin() + 16);
    const std::vector<float> its(r.intensity.begin(), r.intensity.begin() + 16);
    CHECK_FALSE(strongest_line_pair(one_line, its, kPitchEl));
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

TEST_CASE("line profile: the cued tracker keeps a midway drone between the lines while one line's echo fluctuates", "[detect][line_profile]") {
    const double range = 600.0, el_t = 0.5 * kPitchEl;
    DetectorConfig config;
    config.lambda = 180.0;
    DetectorConfig single = config;
    single.line_profile_frames = 1;
    TargetTracker averaged(config, kPaperSensor, {});
    TargetTracker unaveraged(single, kPaperSensor, {});
    const Eigen::Vector3d cue = along(1.0, 0.0, el_t).cast<double>().normalized();
    for (int k = 0; k < 8; ++k) {
        // The upper line's echo 3.5 times stronger, then weaker, frame after frame: more than the
        // trusted ratio in one frame, nothing on average.
        Returns r = point_target(range, 0.0, el_t);
        const float f = k == 0 ? 1.0f : k % 2 ? 3.5f : 1.0f / 3.5f;
        for (std::size_t i = 16; i < r.intensity.size(); ++i) r.intensity[i] *= f;
        const Detection d = averaged.process(k, 0.05 * k, r.points, cue, r.intensity);
        const Detection u = unaveraged.process(k, 0.05 * k, r.points, cue, r.intensity);
        INFO("frame " << k);
        REQUIRE(d.found);
        REQUIRE(u.found);
        CHECK(std::abs(elevation_of(d.sensor_box.centre) - el_t) * range < 1e-3);
        if (k > 0) CHECK(std::abs(elevation_of(u.sensor_box.centre) - el_t) * range > 0.03);
    }
}
