#pragma once
// A scenario for checks against closed forms, and the closed form most of them use.
#include <algorithm>
#include <cmath>

#include "ladarsim/sensor_model/render/scenario.h"
#include "atmospheres.h"
#include "footprint_grid.h"
#include "sensors.h"

namespace ladarsim::test {

/// The paper's sensor with the parts that would blur a closed-form check switched off: no noise
/// (expectations only), no extinction, no range folding, no saturation.
inline sensor_model::Scenario closed_form_scenario() {
    sensor_model::Scenario s;
    s.sensor = paper_sensor();
    s.mount.position_world = {0, 0, 0};
    s.mount.gimbal_az_deg = 0.0;
    s.mount.gimbal_el_deg = 0.0;
    s.render.frames = 1;
    s.render.noise = false;
    s.atmosphere = vacuum();
    s.sensor.receiver.range_folding = false;
    s.sensor.receiver.saturation_current_a = 1e6;
    return s;
}

/// Primary photo-electrons from a Lambertian surface filling the footprint (extended target):
/// E_pulse eta (rho / pi) cos(theta) A_r / R^2, with E_pulse = P_peak FWHM sqrt(pi / (4 ln 2)) for
/// the Gaussian pulse, times responsivity / q.
inline double extended_target_photoelectrons(const sensor_model::Sensor& c, double reflectance, double cos_incidence, double range_m) {
    const double pulse_energy = c.transmitter.peak_power_w * c.transmitter.pulse_width_ns * 1e-9 * std::sqrt(M_PI / (4.0 * std::log(2.0)));
    const double area = M_PI * c.optics.aperture_diameter_m * c.optics.aperture_diameter_m / 4.0;
    const double energy = pulse_energy * c.optics.optics_efficiency * reflectance / M_PI * cos_incidence * area / (range_m * range_m);
    return energy * c.receiver.responsivity_a_per_w / 1.602176634e-19;
}

/// What the waveform's discriminator reports of one surface whose range varies across a circular
/// footprint: the echo's range distribution (midpoint rule over the truncated Gaussian, n x n
/// cells, each weighted by the irradiance and by `echo`'s energy weight) has mean m and standard
/// deviation d; its pulse, of sigma s = sqrt(p^2 + d^2) against the transmitted pulse's p, is timed
/// by its 50 % leading edge plus half the transmitted FWHM, sqrt(2 ln 2) (s - p) before m, and
/// peaks at p / s of the transmitted pulse's peak for the same energy.
struct DiscriminatedEcho {
    double range_m;
    double peak_share;
};
/// `echo(x, y)`: {range, energy weight} of the sub-ray at footprint offsets x (azimuth) and y
/// (elevation), in radians.
template <typename Echo>
DiscriminatedEcho discriminated_echo(const sensor_model::Sensor& c, double truncation, Echo&& echo, int n = 400) {
    const double w = 0.5 * c.transmitter.divergence_mrad * 1e-3;
    double sum = 0.0, sum_r = 0.0, sum_r2 = 0.0;
    for_each_footprint_cell(n, truncation * w, [&](double x, double y) {
        const auto [range, weight] = echo(x, y);
        const double g = std::exp(-2.0 * (x * x + y * y) / (w * w)) * weight;
        sum += g;
        sum_r += g * range;
        sum_r2 += g * range * range;
    });
    const double mean = sum_r / sum, d2 = std::max(0.0, sum_r2 / sum - mean * mean);
    const double p = 0.5 * 299792458.0 * c.transmitter.pulse_width_ns * 1e-9 / (2.0 * std::sqrt(2.0 * std::log(2.0)));
    const double s = std::sqrt(p * p + d2);
    return {mean - std::sqrt(2.0 * std::log(2.0)) * (s - p), p / s};
}


}  // namespace ladarsim::test
