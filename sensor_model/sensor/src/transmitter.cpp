#include "ladarsim/sensor_model/sensor/transmitter.h"

#include <cmath>
#include <numbers>

#include "ladarsim/sensor_model/sensor/physical_constants.h"

namespace ladarsim::sensor_model {

double Transmitter::pulse_energy_j() const {
    return peak_power_w * pulse_width_ns * 1e-9 * std::sqrt(std::numbers::pi / (4.0 * std::numbers::ln2));
}
double Transmitter::average_power_w() const { return pulse_energy_j() * pulse_rate_hz; }
double Transmitter::unambiguous_range_m() const { return kSpeedOfLight_mps / (2.0 * pulse_rate_hz); }

Transmitter Transmitter::read(JsonFields& t) {
    Transmitter x;
    x.wavelength_nm = t.number("wavelength_nm", 200.0, 20000.0);
    x.peak_power_w = t.number("peak_power_w", 1e-6, 1e12);
    x.pulse_width_ns = t.number("pulse_width_ns", 0.01, 1e6);
    x.pulse_rate_hz = t.number("pulse_rate_hz", 1.0, 1e9);
    x.divergence_mrad = t.number("divergence_mrad", 1e-4, 100.0);
    x.divergence_el_mrad = t.number("divergence_el_mrad", 1e-4, 100.0);
    return x;
}

nlohmann::json Transmitter::to_json() const {
    return {{"wavelength_nm", wavelength_nm},     {"peak_power_w", peak_power_w},
            {"pulse_width_ns", pulse_width_ns},   {"pulse_rate_hz", pulse_rate_hz},
            {"divergence_mrad", divergence_mrad}, {"divergence_el_mrad", divergence_el_mrad}};
}

}  // namespace ladarsim::sensor_model
