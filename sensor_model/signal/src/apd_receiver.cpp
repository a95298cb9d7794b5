#include "ladarsim/sensor_model/signal/apd_receiver.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "ladarsim/sensor_model/sensor/physical_constants.h"

namespace ladarsim::sensor_model {

double rice_false_alarm_rate_hz(double tnr, double bandwidth_hz) {
    return bandwidth_hz / std::sqrt(3.0) * std::exp(-0.5 * tnr * tnr);
}

double threshold_to_noise_for(double false_alarm_rate_hz, double bandwidth_hz) {
    const double ratio = bandwidth_hz / std::sqrt(3.0) / false_alarm_rate_hz;
    if (!(ratio > 1.0)) throw std::invalid_argument("false-alarm rate must be below bandwidth / sqrt(3)");
    return std::sqrt(2.0 * std::log(ratio));
}

double solar_background_power_w(const Optics& s, const Atmosphere& a) {
    if (!a.daylight) return 0.0;
    const double half_angle = 0.5e-3 * s.receiver_fov_mrad;
    const double solid_angle = 2.0 * std::numbers::pi * (1.0 - std::cos(half_angle));
    return a.solar_irradiance_w_m2_nm * s.filter_width_nm * a.background_reflectance / std::numbers::pi * solid_angle *
           s.aperture_area_m2() * s.optics_efficiency;
}

PulseShape PulseShape::of(double fwhm_s, double spread_s) {
    const double sigma = fwhm_s / (2.0 * std::sqrt(2.0 * std::numbers::ln2));
    return PulseShape{std::sqrt(sigma * sigma + spread_s * spread_s)};
}

double PulseShape::peak_per_joule() const { return 1.0 / (sigma_s * std::sqrt(2.0 * std::numbers::pi)); }

double PulseShape::rise_time_s() const {
    return sigma_s * (std::sqrt(2.0 * std::log(10.0)) - std::sqrt(2.0 * std::log(10.0 / 9.0)));
}

double PulseShape::at(double t_s) const {
    const double x = t_s / sigma_s;
    return peak_per_joule() * std::exp(-0.5 * x * x);
}

ApdReceiver::ApdReceiver(const Receiver& s, double background_power_w)
    : gain_(s.apd_gain),
      responsivity_(s.responsivity_a_per_w),
      excess_noise_(s.excess_noise_factor),
      bandwidth_(s.bandwidth_hz),
      dark_current_(s.dark_current_a),
      thermal_variance_(4.0 * kBoltzmann_j_per_k * s.temperature_k * s.bandwidth_hz / s.load_resistance_ohm),
      background_(background_power_w),
      saturation_(s.saturation_current_a),
      tnr_(threshold_to_noise_for(s.false_alarm_rate_hz, s.bandwidth_hz)) {}

double ApdReceiver::noise_a(double signal_power_w) const {
    const double primary = responsivity_ * (signal_power_w + background_) + dark_current_;
    return std::sqrt(2.0 * kElementaryCharge_c * bandwidth_ * gain_ * gain_ * excess_noise_ * primary + thermal_variance_);
}

double ApdReceiver::range_jitter_m(double peak_power_w, const PulseShape& pulse) const {
    const double amplitude = amps_per_watt() * peak_power_w;
    if (!(amplitude > 0.0)) return 0.0;
    const double half_width = pulse.sigma_s * std::sqrt(2.0 * std::numbers::ln2);
    const double slope = 0.5 * amplitude * half_width / (pulse.sigma_s * pulse.sigma_s);
    const double x = 2.0 * std::numbers::pi * bandwidth_ * half_width;
    const double rho = std::sin(x) / x;
    const double s_c = noise_a(0.5 * peak_power_w), s_p = noise_a(peak_power_w);
    const double variance = s_c * s_c + 0.25 * s_p * s_p - rho * s_c * s_p;
    return 0.5 * kSpeedOfLight_mps * std::sqrt(std::max(variance, 0.0)) / slope;
}

}  // namespace ladarsim::sensor_model
