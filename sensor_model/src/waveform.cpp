#include "ladarsim/sensor_model/waveform.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "ladarsim/sensor_model/physical_constants.h"

namespace ladarsim::sensor_model {
namespace {

/// Blackman-windowed sinc low-pass with cutoff `cutoff` (fraction of the sampling rate), scaled to
/// unit energy so that white unit-variance input gives unit-variance output. 513 taps keep the
/// transition band near 5.5 / 513 of the sampling rate (86 MHz at 8 GHz): close enough to the
/// rectangular band the Rice formula assumes.
std::vector<double> low_pass_taps(double cutoff, int taps) {
    std::vector<double> h(static_cast<std::size_t>(taps));
    const int m = taps - 1;
    double energy = 0.0;
    for (int k = 0; k <= m; ++k) {
        const double x = k - 0.5 * m;
        const double sinc = x == 0.0 ? 2.0 * cutoff : std::sin(2.0 * std::numbers::pi * cutoff * x) / (std::numbers::pi * x);
        const double window = 0.42 - 0.5 * std::cos(2.0 * std::numbers::pi * k / m) + 0.08 * std::cos(4.0 * std::numbers::pi * k / m);
        h[static_cast<std::size_t>(k)] = sinc * window;
        energy += h[static_cast<std::size_t>(k)] * h[static_cast<std::size_t>(k)];
    }
    for (double& v : h) v /= std::sqrt(energy);
    return h;
}

constexpr double kWindowSigmas = 6.0;  // pulse tails kept on each side of a cluster of echoes

}  // namespace

WaveformReceiver::WaveformReceiver(const ApdReceiver& apd, double pulse_fwhm_s, double bin_s)
    : apd_(apd), pulse_(PulseShape::of(pulse_fwhm_s)), fwhm_s_(pulse_fwhm_s), bin_s_(bin_s),
      taps_(low_pass_taps(std::min(0.5, apd.bandwidth_hz() * bin_s), 513)) {}

std::vector<double> WaveformReceiver::band_limited_noise(std::size_t n, RandomSequence& rng) const {
    const std::size_t taps = taps_.size();
    std::vector<double> white(n + taps - 1);
    for (double& w : white) w = rng.normal();
    std::vector<double> out(n);
    for (std::size_t i = 0; i < n; ++i) {
        double acc = 0.0;
        for (std::size_t k = 0; k < taps; ++k) acc += taps_[k] * white[i + k];
        out[i] = acc;
    }
    return out;
}

std::vector<DetectedPulse> WaveformReceiver::detect(std::span<const Echo> echoes, RandomSequence* noise) const {
    std::vector<Echo> sorted(echoes.begin(), echoes.end());
    std::sort(sorted.begin(), sorted.end(), [](const Echo& a, const Echo& b) { return a.range_m < b.range_m; });
    std::vector<DetectedPulse> pulses;
    const double to_time = 2.0 / kSpeedOfLight_mps;
    const double margin_s = kWindowSigmas * pulse_.sigma_s;
    for (std::size_t first = 0; first < sorted.size();) {
        std::size_t last = first + 1;
        while (last < sorted.size() && (sorted[last].range_m - sorted[last - 1].range_m) * to_time < 2.0 * margin_s) ++last;
        const double t0 = sorted[first].range_m * to_time - margin_s;
        const double t1 = sorted[last - 1].range_m * to_time + margin_s;
        const auto bins = static_cast<std::size_t>(std::ceil((t1 - t0) / bin_s_)) + 1;
        detect_window(std::span(sorted).subspan(first, last - first), t0, bins, noise, pulses);
        first = last;
    }
    return pulses;
}

void WaveformReceiver::detect_window(std::span<const Echo> echoes, double t0_s, std::size_t bins, RandomSequence* noise,
                                     std::vector<DetectedPulse>& out) const {
    const double to_time = 2.0 / kSpeedOfLight_mps;
    const double amps_per_watt = apd_.amps_per_watt();
    std::vector<double> power(bins, 0.0);
    for (const Echo& e : echoes) {
        const double te = e.range_m * to_time;
        // Only bins within the kept tails of this echo.
        const double lo = (te - kWindowSigmas * pulse_.sigma_s - t0_s) / bin_s_;
        const double hi = (te + kWindowSigmas * pulse_.sigma_s - t0_s) / bin_s_;
        const auto k0 = static_cast<std::size_t>(std::max(0.0, std::floor(lo)));
        const auto k1 = std::min(bins - 1, static_cast<std::size_t>(std::max(0.0, std::ceil(hi))));
        for (std::size_t k = k0; k <= k1; ++k) power[k] += e.energy_j * pulse_.at(t0_s + k * bin_s_ - te);
    }
    const std::vector<double> n = noise ? band_limited_noise(bins, *noise) : std::vector<double>(bins, 0.0);
    std::vector<double> y(bins);
    const double saturation = apd_.saturation_a();
    for (std::size_t k = 0; k < bins; ++k)
        y[k] = std::min(amps_per_watt * power[k] + apd_.noise_a(power[k]) * n[k], saturation);

    const double threshold = apd_.threshold_a();
    const double floor_noise = apd_.noise_floor_a();
    std::uint32_t surfaces = 0;
    for (const Echo& e : echoes) surfaces = std::max(surfaces, e.surface + 1);
    std::vector<double> contribution(surfaces);
    auto finish = [&](std::size_t peak) {
        // The sampled maximum misses the true peak by up to half a bin (1 % in height for a 1 ns
        // pulse); a parabola through the logarithms of the three samples about it is exact for a
        // Gaussian pulse.
        double offset = 0.0, peak_value = y[peak];
        if (peak > 0 && peak + 1 < bins && y[peak - 1] > 0.0 && y[peak + 1] > 0.0 && y[peak] < saturation) {
            const double a = std::log(y[peak - 1]), b = std::log(y[peak]), c = std::log(y[peak + 1]);
            const double curvature = a - 2.0 * b + c;
            if (curvature < 0.0) {
                offset = std::clamp(0.5 * (a - c) / curvature, -0.5, 0.5);
                peak_value = std::exp(b - 0.25 * (a - c) * offset);
            }
        }
        // 50 % leading-edge crossing of the measured peak, searched back from the peak; the pulse
        // centre lies half a FWHM after it for the Gaussian pulse.
        const double level = 0.5 * peak_value;
        std::size_t k = peak;
        while (k > 0 && y[k - 1] >= level) --k;
        double t_cross;
        if (k == 0) {
            t_cross = t0_s;
        } else {
            const double f = (level - y[k - 1]) / (y[k] - y[k - 1]);
            t_cross = t0_s + (static_cast<double>(k - 1) + f) * bin_s_;
        }
        const double t_peak = t0_s + (static_cast<double>(peak) + offset) * bin_s_;
        // Which surface made it: the largest noise-free contribution at the peak.
        std::fill(contribution.begin(), contribution.end(), 0.0);
        for (const Echo& e : echoes) contribution[e.surface] += e.energy_j * pulse_.at(t_peak - e.range_m * to_time);
        std::uint32_t surface = kNoSurface;
        double best = 0.0;
        for (std::uint32_t i = 0; i < surfaces; ++i) {
            if (contribution[i] > best) {
                best = contribution[i];
                surface = i;
            }
        }
        const double signal = amps_per_watt * power[peak];
        // A peak the echoes barely touch is the noise's, not theirs.
        if (signal < floor_noise) surface = kNoSurface;
        DetectedPulse p;
        p.range_m = 0.5 * kSpeedOfLight_mps * (t_cross + 0.5 * fwhm_s_);
        p.peak_a = peak_value;
        p.snr = surface == kNoSurface ? peak_value / floor_noise : signal / apd_.noise_a(power[peak]);
        p.saturated = y[peak] >= saturation;
        p.surface = surface;
        out.push_back(p);
    };

    // Excursions above the threshold; inside one, a dip below half its peak followed by a rise to
    // more than twice the dip (and 3 noise sigmas above it) starts a new pulse.
    bool inside = false, in_valley = false;
    std::size_t peak = 0, valley = 0;
    for (std::size_t k = 0; k < bins; ++k) {
        if (y[k] <= threshold) {
            if (inside) finish(peak);
            inside = in_valley = false;
            continue;
        }
        if (!inside) {
            inside = true;
            in_valley = false;
            peak = k;
        } else if (!in_valley) {
            if (y[k] > y[peak]) peak = k;
            else if (y[k] < 0.5 * y[peak]) in_valley = true, valley = k;
        } else if (y[k] < y[valley]) {
            valley = k;
        } else if (y[k] > 2.0 * y[valley] && y[k] - y[valley] > 3.0 * floor_noise) {
            finish(peak);
            peak = k;
            in_valley = false;
        }
    }
    if (inside) finish(peak);
}

}  // namespace ladarsim::sensor_model
