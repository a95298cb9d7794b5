#pragma once
// The InGaAs APD receiver: noise, threshold, detection, timing jitter and saturation.
#include "ladarsim/sensor_model/signal/atmosphere.h"
#include "ladarsim/sensor_model/sensor/optics.h"
#include "ladarsim/sensor_model/sensor/receiver.h"

namespace ladarsim::sensor_model {

/// Rate (1/s) at which Gaussian noise of rectangular bandwidth B crosses a threshold of `tnr`
/// standard deviations upwards (Rice 1944): B / sqrt(3) * exp(-tnr^2 / 2).
double rice_false_alarm_rate_hz(double tnr, double bandwidth_hz);
/// The threshold-to-noise ratio giving that rate: the inverse of rice_false_alarm_rate_hz.
double threshold_to_noise_for(double false_alarm_rate_hz, double bandwidth_hz);

/// Sunlight scattered by the scene into the receiver (W): E_sun(lambda) * filter width * (rho / pi)
/// * solid angle of the receiver field * aperture area * optics efficiency; 0 at night.
double solar_background_power_w(const Optics& optics, const Atmosphere& atmosphere);

/// A Gaussian pulse of unit energy, FWHM `fwhm_s`, stretched by the spread of arrival times of the
/// sub-ray echoes that make one return (their energy-weighted standard deviation `spread_s`):
/// the convolution of two Gaussians is a Gaussian with the variances added.
struct PulseShape {
    double sigma_s;
    static PulseShape of(double fwhm_s, double spread_s = 0.0);
    double peak_per_joule() const;  ///< peak power (W) per joule of pulse energy: 1 / (sigma sqrt(2 pi))
    double rise_time_s() const;     ///< 10 % to 90 %: sigma (sqrt(2 ln 10) - sqrt(2 ln (10/9)))
    double at(double t_s) const;    ///< power (W) per joule at time t from the peak
};

class ApdReceiver {
public:
    ApdReceiver(const Receiver& receiver, double background_power_w);

    /// Output current per watt of optical power: gain x responsivity.
    double amps_per_watt() const { return gain_ * responsivity_; }
    /// RMS noise current with `signal_power_w` on the detector:
    ///   sqrt(2 q B M^2 F (R0 (P_s + P_bg) + I_d) + 4 k T B / R_L).
    double noise_a(double signal_power_w) const;
    double noise_floor_a() const { return noise_a(0.0); }
    double threshold_to_noise() const { return tnr_; }
    double threshold_a() const { return tnr_ * noise_floor_a(); }
    /// The false-alarm rate this threshold gives (the target rate, by construction; kept to test).
    double false_alarm_rate_hz() const { return rice_false_alarm_rate_hz(tnr_, bandwidth_); }
    double saturation_a() const { return saturation_; }
    double background_power_w() const { return background_; }
    double bandwidth_hz() const { return bandwidth_; }
    /// Range standard deviation of a pulse of peak optical power `peak_power_w` timed by the
    /// discriminator (the 50 % crossing of its measured peak, see WaveformReceiver). To first
    /// order the crossing moves by (n_c - n_p / 2) / slope, n_c and n_p the noise at the crossing
    /// and at the peak, a time d = sigma sqrt(2 ln 2) apart, where the slope is A sqrt(2 ln 2) / (2 sigma):
    ///   sigma_t = sqrt(s_c^2 + s_p^2 / 4 - rho s_c s_p) / slope,   rho = sinc(2 B d),
    /// s_c and s_p the noise there (shot noise follows the signal) and rho the correlation of noise
    /// band-limited to B. It is 0.5-0.8 x the textbook (c/2) t_rise / SNR, which ignores both.
    double range_jitter_m(double peak_power_w, const PulseShape& pulse) const;

private:
    double gain_, responsivity_, excess_noise_, bandwidth_, dark_current_, thermal_variance_;
    double background_, saturation_, tnr_;
};

}  // namespace ladarsim::sensor_model
