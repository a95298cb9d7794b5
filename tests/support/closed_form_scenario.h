#pragma once
// A scenario for checks against closed forms, and the closed form most of them use.
#include <cmath>

#include "ladarsim/sensor_model/render/scenario.h"
#include "atmospheres.h"
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


}  // namespace ladarsim::test
