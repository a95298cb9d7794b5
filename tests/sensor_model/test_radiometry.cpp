// The rendered sub-ray sum against the range equation's closed forms: the extended-target limit
// (1/R^2), the point-target limit (1/R^4) and the crossover between them.
#include <catch2/catch.hpp>

#include <cmath>

#include "ladarsim/sensor_model/render/frame_renderer.h"
#include "ladarsim/sensor_model/signal/range_equation.h"
#include "../support/closed_form_scenario.h"
#include "../support/sensors.h"
#include "../support/scene_builders.h"

using namespace ladarsim;
using namespace ladarsim::sensor_model;
using namespace ladarsim::test;

namespace {

constexpr double kDiscRadius = 0.15;  // the paper's 0.3 m target
constexpr int kSegments = 64;
constexpr double kReflectance = 0.5;

/// Area of the 64-gon that stands for the disc.
double polygon_area() { return 0.5 * kSegments * kDiscRadius * kDiscRadius * std::sin(2.0 * M_PI / kSegments); }

/// One beam, the disc centred on its axis at `range_m`; mean photo-electrons over `frames`
/// jittered footprints. Noise, extinction and saturation are off, and the laser is strong enough
/// that the threshold never hides a return: what is left is geometry and the range equation.
double rendered_photoelectrons(double range_m, int frames, Sensor& sensor_out) {
    Scenario s = closed_form_scenario();
    set_raster(s.sensor, 1, 1, 1e-3, 1e-3);
    s.render.footprint_samples = 4096;
    s.sensor.transmitter.peak_power_w = 1e12;
    s.sensor.receiver.saturation_current_a = 1e9;
    s.sensor.receiver.max_range_m = 1e6;
    s.scene.objects.push_back(object_at(1, disc(kDiscRadius, kSegments, kReflectance), fixed_at(range_m, 0, 0)));
    sensor_out = s.sensor;
    FrameRenderer renderer(s);
    double sum = 0.0;
    for (int f = 0; f < frames; ++f) {
        const Frame frame = renderer.render(static_cast<std::uint64_t>(f));
        REQUIRE(frame.returns.size() == 1);
        sum += frame.returns[0].intensity;
    }
    return sum / frames;
}

/// Photo-electrons if the whole pulse fell on the disc's Lambertian surface facing the sensor.
double extended(const Sensor& c, double range_m) { return extended_target_photoelectrons(c, kReflectance, 1.0, range_m); }

/// Fraction of the footprint's energy on the disc. The footprint is Gaussian with 1/e^2 radius
/// w = theta R / 2, truncated at 1.5 w (holding F = 1 - exp(-4.5)) and renormalised: a centred disc
/// of radius a holds (1 - exp(-2 a^2 / w^2)) / F, or all of it once a passes the truncation.
double on_disc_fraction(const Sensor& c, double range_m) {
    const double w = 0.5 * c.transmitter.divergence_mrad * 1e-3 * range_m;
    const double a = std::sqrt(polygon_area() / M_PI);
    if (a >= kTruncation * w) return 1.0;
    const double f = 1.0 - std::exp(-2.0 * kTruncation * kTruncation);
    return (1.0 - std::exp(-2.0 * a * a / (w * w))) / f;
}

/// Point-target limit: the disc small against the footprint, lit by the peak irradiance
/// 2 / (pi w^2 F) of the truncated Gaussian: energy fraction 2 A / (pi w^2 F), falling as 1/R^2 on
/// top of the range equation's own 1/R^2.
double point_fraction(const Sensor& c, double range_m) {
    const double w = 0.5 * c.transmitter.divergence_mrad * 1e-3 * range_m;
    const double f = 1.0 - std::exp(-2.0 * kTruncation * kTruncation);
    return 2.0 * polygon_area() / (M_PI * w * w * f);
}

}  // namespace

TEST_CASE("extended-target limit: a disc filling the footprint returns E eta rho A_r / (pi R^2)", "[radiometry]") {
    for (double range : {20.0, 100.0}) {
        Sensor c = sensor_preset("paper_ladar");
        const double got = rendered_photoelectrons(range, 1, c);
        // The renderer's exact view factor r^2 / (R^2 + r^2) differs from A_r / (pi R^2) by
        // (r / R)^2 = 1.6e-6 at 20 m.
        CHECK(got == Approx(extended(c, range)).epsilon(1e-5));
    }
}

TEST_CASE("point-target limit and the transition: the sub-ray sum follows the Gaussian footprint", "[radiometry]") {
    // Between the limits the reference is the exact fraction of a centred disc; far out it is the
    // point-target equation (1/R^4), within 0.4 % of the exact fraction at 8 km.
    for (double range : {300.0, 700.0, 1500.0, 3000.0}) {
        Sensor c = sensor_preset("paper_ladar");
        const double got = rendered_photoelectrons(range, 32, c);
        INFO("range " << range << " m");
        CHECK(got == Approx(extended(c, range) * on_disc_fraction(c, range)).epsilon(0.01));
    }
    Sensor c = sensor_preset("paper_ladar");
    const double far = 8000.0;
    const double got = rendered_photoelectrons(far, 64, c);
    CHECK(got == Approx(extended(c, far) * point_fraction(c, far)).epsilon(0.01));
}

TEST_CASE("crossover: the 1/R^2 and 1/R^4 asymptotes of the rendered sum meet where the closed forms say", "[radiometry]") {
    Sensor c = sensor_preset("paper_ladar");
    const double near = 50.0, far = 8000.0;
    const double c2 = rendered_photoelectrons(near, 1, c) * near * near;        // E = C2 / R^2
    const double c4 = rendered_photoelectrons(far, 64, c) * std::pow(far, 4.0);  // E = C4 / R^4
    const double crossover = std::sqrt(c4 / c2);
    // Asymptotes meet where 2 A / (pi w^2 F) = 1, w = theta R / 2: R = (2 / theta) sqrt(2 A / (pi F)).
    // For the disc's diameter D this is (D / theta) sqrt(2 / F) = 688 m; the paper's 484 m = D / theta
    // is the same construction for a flat-top beam, whose irradiance is half the Gaussian's peak.
    const double f = 1.0 - std::exp(-2.0 * kTruncation * kTruncation);
    const double theta = c.transmitter.divergence_mrad * 1e-3;
    const double expected = 2.0 / theta * std::sqrt(2.0 * polygon_area() / (M_PI * f));
    CHECK(crossover == Approx(expected).epsilon(0.10));
    CHECK(expected == Approx(0.3 / theta * std::sqrt(2.0 / f)).epsilon(0.002));
    WARN("rendered crossover " << crossover << " m; Gaussian closed form " << expected << " m; flat-top (paper) "
                               << 0.3 / theta << " m");
}

TEST_CASE("speckle cells: a 0.3 m drone at 2 km fluctuates by about 20 %, a full footprint far less", "[radiometry]") {
    // physics.md: about 20 % for a drone at 2 km with this sensor.
    const double drone = speckle_cells(1560e-9, 2000.0, 0.3, 0.05);
    CHECK(1.0 / std::sqrt(drone) == Approx(0.2).margin(0.03));
    const double wall = speckle_cells(1560e-9, 2000.0, 1.24, 0.05);
    CHECK(1.0 / std::sqrt(wall) < 0.06);
}

TEST_CASE("no echo carries more than the pulse, however close the surface", "[radiometry]") {
    const double area = M_PI / 4.0 * 0.05 * 0.05;
    for (double range : {0.0, 1e-6, 1e-3, 0.025, 1.0, 10.0}) {
        const double e = lambertian_echo_energy_j(1.0, 1.0, 1.0, 1.0, 1.0, 1.0, area, range);
        CHECK(e <= 1.0);
        CHECK(std::isfinite(e));
    }
    // At R = r_a a white surface sends half its light into the aperture (view factor 1/2).
    CHECK(lambertian_echo_energy_j(1.0, 1.0, 1.0, 1.0, 1.0, 1.0, area, 0.025) == Approx(0.5));
}
