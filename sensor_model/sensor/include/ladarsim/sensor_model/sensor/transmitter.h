#pragma once
// The laser: what leaves the sensor with every pulse.
#include <nlohmann/json.hpp>

#include "ladarsim/core/json_fields.h"

namespace ladarsim::sensor_model {

struct Transmitter {
    double wavelength_nm = 0.0;
    double peak_power_w = 0.0;
    double pulse_width_ns = 0.0;      ///< full width at half maximum of a Gaussian pulse
    double pulse_rate_hz = 0.0;     ///< laser repetition rate (several pulses per beam position)
    double divergence_mrad = 0.0;    ///< full angle at the 1/e^2 irradiance radius, in azimuth
    double divergence_el_mrad = 0.0; ///< the same in elevation (elliptical beams)

    double pulse_energy_j() const;       ///< peak power x FWHM x sqrt(pi / (4 ln 2)) (Gaussian)
    double average_power_w() const;      ///< pulse energy x pulse rate
    double unambiguous_range_m() const;  ///< c / (2 * pulse rate)

    /// Every key required; throws InputError naming it.
    static Transmitter read(JsonFields& transmitter);
    nlohmann::json to_json() const;
};

}  // namespace ladarsim::sensor_model
