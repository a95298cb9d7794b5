#include "ladarsim/sensor_model/signal/waveform.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <map>
#include <mutex>
#include <numbers>

#include <unsupported/Eigen/FFT>

#include "ladarsim/sensor_model/sensor/physical_constants.h"

namespace ladarsim::sensor_model {
namespace {

constexpr double kWindowSigmas = 6.0;  // pulse tails kept on each side of a cluster of echoes
constexpr std::size_t kNoiseBank = std::size_t{1} << 18;  // samples: 33 us of receiver noise
constexpr std::size_t kShortWindow = 2048;  // bins (38 m): built whole, cheaper than bounding it

}  // namespace

WaveformReceiver::WaveformReceiver(const ApdReceiver& apd, double pulse_fwhm_s, double bin_s)
    : apd_(apd), pulse_(PulseShape::of(pulse_fwhm_s)), fwhm_s_(pulse_fwhm_s), bin_s_(bin_s) {
    static std::mutex banks_mutex;
    static std::map<double, std::shared_ptr<const std::vector<double>>> banks;  // by bandwidth x bin
    const std::lock_guard lock(banks_mutex);
    auto& bank = banks[apd_.bandwidth_hz() * bin_s_];
    if (!bank) {
        RandomSequence bank_draws(0, RandomStream::waveform_noise, 0, 0xFFFFFFFFu);
        bank = std::make_shared<const std::vector<double>>(band_limited_noise(kNoiseBank, bank_draws));
    }
    noise_bank_ = bank;
}

PulseShape WaveformReceiver::shape_of(const Echo& e) const {
    return e.spread_m > 0.0 ? PulseShape::of(fwhm_s_, 2.0 * e.spread_m / kSpeedOfLight_mps) : pulse_;
}

std::vector<double> WaveformReceiver::band_limited_noise(std::size_t n, RandomSequence& rng) const {
    // Spectral synthesis: independent Gaussian Fourier coefficients on every frequency up to the
    // bandwidth, none above, and one inverse FFT. The spectrum is exactly rectangular (what the Rice
    // rate assumes) and the cost O(N log N), against O(N x taps) for a long low-pass FIR.
    std::size_t size = 64;
    while (size < n) size *= 2;
    const auto top = static_cast<std::size_t>(std::floor(apd_.bandwidth_hz() * bin_s_ * static_cast<double>(size)));
    const std::size_t bands = std::min(top, size / 2 - 1);
    std::vector<std::complex<double>> spectrum(size, 0.0);
    spectrum[0] = rng.normal();
    for (std::size_t j = 1; j <= bands; ++j) {
        spectrum[j] = std::complex<double>(rng.normal(), rng.normal()) / std::sqrt(2.0);
        spectrum[size - j] = std::conj(spectrum[j]);
    }
    std::vector<std::complex<double>> samples;
    Eigen::FFT<double> fft;
    fft.inv(samples, spectrum);
    // Eigen's inverse divides by N: each sample has variance (1 + 2 bands) / N^2.
    const double scale = static_cast<double>(size) / std::sqrt(1.0 + 2.0 * static_cast<double>(bands));
    std::vector<double> out(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = samples[i].real() * scale;
    return out;
}

std::vector<DetectedPulse> WaveformReceiver::detect(std::span<const Echo> echoes, RandomSequence* noise) const {
    std::vector<DetectedPulse> pulses;
    detect(echoes, noise, pulses);
    return pulses;
}

void WaveformReceiver::detect(std::span<const Echo> echoes, RandomSequence* noise, std::vector<DetectedPulse>& pulses,
                              std::vector<WaveformWindow>* windows) const {
    const double to_time = 2.0 / kSpeedOfLight_mps;
    // Each echo's kept pulse: kWindowSigmas of its own width each side of its centre.
    struct Reach {
        double begin_s, end_s;
        double peak_w;  ///< its pulse's peak power
        std::size_t echo;
    };
    thread_local std::vector<Reach> reach;
    reach.clear();
    double peaks = 0.0;
    for (std::size_t i = 0; i < echoes.size(); ++i) {
        const PulseShape shape = shape_of(echoes[i]);
        const double te = echoes[i].range_m * to_time;
        reach.push_back({te - kWindowSigmas * shape.sigma_s, te + kWindowSigmas * shape.sigma_s,
                         echoes[i].energy_j * shape.peak_per_joule(), i});
        peaks += reach.back().peak_w;
    }
    // Even with every pulse's peak at one instant the signal stays below the threshold: nothing to
    // detect (what noise alone crosses is the false-alarm process).
    if (reach_a(peaks, noise != nullptr) <= apd_.threshold_a()) return;
    // Windows where the kept pulses overlap (by their own widths: one echo stretched over tens of
    // metres does not widen the window around another a kilometre away); each window's echoes
    // sorted by range.
    std::sort(reach.begin(), reach.end(), [](const Reach& a, const Reach& b) { return a.begin_s < b.begin_s; });
    thread_local std::vector<Echo> window;
    for (std::size_t first = 0; first < reach.size();) {
        double end = reach[first].end_s, window_peaks = reach[first].peak_w;
        std::size_t last = first + 1;
        for (; last < reach.size() && reach[last].begin_s < end; ++last) {
            end = std::max(end, reach[last].end_s);
            window_peaks += reach[last].peak_w;
        }
        if (reach_a(window_peaks, noise != nullptr) <= apd_.threshold_a()) {  // the same, window by window
            first = last;
            continue;
        }
        window.clear();
        for (std::size_t k = first; k < last; ++k) window.push_back(echoes[reach[k].echo]);
        std::sort(window.begin(), window.end(), [](const Echo& a, const Echo& b) { return a.range_m < b.range_m; });
        const double t0 = reach[first].begin_s;
        const auto bins = static_cast<std::size_t>(std::ceil((end - t0) / bin_s_)) + 1;
        // A long window (a grazing footprint's) is built only where pulses can be detected.
        if (bins <= kShortWindow) {
            detect_window(window, t0, bins, noise, pulses, windows);
        } else {
            for (const LiveSpan& live : live_spans(window, t0, bins, noise != nullptr))
                detect_window(std::span(window).subspan(live.first_echo, live.echoes), t0 + live.first_bin * bin_s_, live.bins, noise,
                              pulses, windows);
        }
        first = last;
    }
}

double WaveformReceiver::reach_a(double power_w, bool noisy) const {
    return apd_.amps_per_watt() * power_w + (noisy ? 2.0 * apd_.noise_a(power_w) : 0.0);
}

std::vector<WaveformReceiver::LiveSpan> WaveformReceiver::live_spans(std::span<const Echo> echoes, double t0_s, std::size_t bins,
                                                                     bool noisy) const {
    // An upper bound of the noise-free signal on a coarse grid, each echo's pulse bounded by a
    // staircase (its peak within one sigma of its centre, exp(-k^2 / 2) of it from k sigmas, and
    // nothing beyond the kWindowSigmas the waveform keeps), summed with a difference array: a
    // handful of operations per echo however far its pulse is stretched.
    constexpr std::size_t kCoarse = 32;  // fine bins per coarse bin: 4 ns, 0.6 m
    const double to_time = 2.0 / kSpeedOfLight_mps;
    const double coarse_s = kCoarse * bin_s_;
    const std::size_t coarse = bins / kCoarse + 1;
    thread_local std::vector<double> bound;
    bound.assign(coarse + 1, 0.0);
    auto add = [&](double a_s, double b_s, double value) {
        const auto c0 = static_cast<std::size_t>(std::clamp(std::floor((a_s - t0_s) / coarse_s), 0.0, double(coarse - 1)));
        const auto c1 = static_cast<std::size_t>(std::clamp(std::floor((b_s - t0_s) / coarse_s), 0.0, double(coarse - 1)));
        bound[c0] += value;
        bound[c1 + 1] -= value;
    };
    static const std::array<double, 6> kStairs = {1.0, std::exp(-0.5), std::exp(-2.0), std::exp(-4.5), std::exp(-8.0), std::exp(-12.5)};
    static_assert(kWindowSigmas == 6.0);
    thread_local std::vector<double> reach_begin, reach_end;
    reach_begin.resize(echoes.size());
    reach_end.resize(echoes.size());
    for (std::size_t i = 0; i < echoes.size(); ++i) {
        const PulseShape shape = shape_of(echoes[i]);
        const double te = echoes[i].range_m * to_time, peak = echoes[i].energy_j * shape.peak_per_joule();
        reach_begin[i] = te - kWindowSigmas * shape.sigma_s;
        reach_end[i] = te + kWindowSigmas * shape.sigma_s;
        if (reach_end[i] - reach_begin[i] <= coarse_s) {
            add(reach_begin[i], reach_end[i], peak);  // within a coarse bin or two: its peak bounds it
            continue;
        }
        for (int k = 0; k < 6; ++k) {
            const double value = peak * kStairs[static_cast<std::size_t>(k)];
            add(te + k * shape.sigma_s, te + (k + 1) * shape.sigma_s, value);
            add(te - (k + 1) * shape.sigma_s, te - k * shape.sigma_s, value);
        }
    }
    for (std::size_t c = 1; c < coarse; ++c) bound[c] += bound[c - 1];

    // Only where the signal (with two noise sigmas, when noisy: reach_a) can reach half the threshold can a
    // pulse's excursion be (it starts above the threshold and ends below half of it); a stretch
    // that never reaches the threshold itself holds no pulse. Elsewhere the waveform is not built:
    // a noise-free one would be below the release level there, and a noisy one crosses the
    // threshold at the rate of noise alone, which the false-alarm process already draws.
    auto reach = [&](double power_w) { return reach_a(power_w, noisy); };
    const double release = release_a(), threshold = apd_.threshold_a();
    std::vector<LiveSpan> spans;
    for (std::size_t c = 0; c < coarse;) {
        if (reach(bound[c]) <= release) {
            ++c;
            continue;
        }
        std::size_t end = c;
        bool crosses = false;
        for (; end < coarse && reach(bound[end]) > release; ++end) crosses = crosses || reach(bound[end]) > threshold;
        if (crosses) {
            // One coarse bin of margin each side, where the signal is below the release level.
            const std::size_t b0 = (c > 0 ? c - 1 : 0) * kCoarse;
            const std::size_t b1 = std::min(bins, (end + 1) * kCoarse);
            const double s0 = t0_s + b0 * bin_s_, s1 = t0_s + b1 * bin_s_;
            // The echoes whose kept tails reach into the span.
            std::size_t first = 0, last = 0;
            bool any = false;
            for (std::size_t i = 0; i < echoes.size(); ++i) {
                if (reach_end[i] < s0 || reach_begin[i] > s1) continue;
                if (!any) first = i;
                last = i + 1;
                any = true;
            }
            if (any) spans.push_back({b0, b1 - b0, first, last - first});
        }
        c = end;
    }
    return spans;
}

struct WaveformReceiver::Window {
    std::span<const Echo> echoes;
    std::span<const PulseShape> shapes;  ///< each echo's
    double t0_s;
    std::size_t bins;
    const std::vector<double>& power;    ///< noise-free, watts
    const std::vector<double>& y;        ///< the detector's current, noise and clipping included
    std::uint32_t surfaces;              ///< one more than the largest surface index of the echoes
    std::vector<double>& contribution;   ///< scratch, by surface
};

void WaveformReceiver::detect_window(std::span<const Echo> echoes, double t0_s, std::size_t bins, RandomSequence* noise,
                                     std::vector<DetectedPulse>& out, std::vector<WaveformWindow>* windows) const {
    // Per-thread scratch: a beam's windows are a few hundred bins.
    thread_local std::vector<double> power, n, y, contribution;
    // Each echo's pulse shape, found once for the sum and the attribution of peaks below.
    thread_local std::vector<PulseShape> shapes;
    shapes.clear();
    for (const Echo& e : echoes) shapes.push_back(shape_of(e));
    sum_pulses(echoes, shapes, t0_s, bins, power);
    n.assign(bins, 0.0);
    if (noise && bins <= kNoiseBank / 8) {
        const auto start = static_cast<std::size_t>(noise->uniform() * static_cast<double>(kNoiseBank - bins));
        std::copy_n(noise_bank_->begin() + static_cast<std::ptrdiff_t>(start), bins, n.begin());
    } else if (noise) {
        n = band_limited_noise(bins, *noise);  // a window longer than the bank can spare
    }
    y.resize(bins);
    const double amps_per_watt = apd_.amps_per_watt();
    const double saturation = apd_.saturation_a();
    for (std::size_t k = 0; k < bins; ++k)
        y[k] = std::min(amps_per_watt * power[k] + (noise ? apd_.noise_a(power[k]) * n[k] : 0.0), saturation);
    if (windows) {
        WaveformWindow& recorded = windows->emplace_back();
        recorded.start_s = t0_s;
        recorded.samples_a.assign(y.begin(), y.end());
    }

    const double threshold = apd_.threshold_a();
    const double floor_noise = apd_.noise_floor_a();
    std::uint32_t surfaces = 0;
    for (const Echo& e : echoes) surfaces = std::max(surfaces, e.surface + 1);
    contribution.assign(surfaces, 0.0);
    const Window w{echoes, shapes, t0_s, bins, power, y, surfaces, contribution};
    // The 50 % crossing of a pulse is searched back no further than where the previous one ended.
    std::size_t searched_to = 0;
    // Excursions: one starts when the signal crosses the threshold and ends when it falls below
    // the release level (release_a). Inside one, a dip below half its peak followed by a rise to more than twice
    // the dip (and 3 noise sigmas above it) starts a new pulse.
    const double release = release_a();
    bool inside = false, in_valley = false;
    std::size_t peak = 0, valley = 0;
    for (std::size_t k = 0; k < bins; ++k) {
        if (inside ? y[k] <= release : y[k] <= threshold) {
            if (inside) out.push_back(measure(w, peak, searched_to));
            if (inside) searched_to = k;
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
            out.push_back(measure(w, peak, searched_to));
            searched_to = valley;
            peak = k;
            in_valley = false;
        }
    }
    if (inside) out.push_back(measure(w, peak, searched_to));
}

void WaveformReceiver::sum_pulses(std::span<const Echo> echoes, std::span<const PulseShape> shapes, double t0_s, std::size_t bins,
                                  std::vector<double>& power) const {
    const double to_time = 2.0 / kSpeedOfLight_mps;
    power.assign(bins, 0.0);
    // The Gaussian across evenly spaced bins by its recurrence: with t_k = t0 + k b - te,
    // g(t_{k+1}) = g(t_k) r_k and r_{k+1} = r_k exp(-b^2 / sigma^2): three exponentials per
    // echo instead of one per bin (a beam can carry hundreds of sub-ray echoes).
    struct Recurrence {
        std::size_t k0, k1;  // only bins within the kept tails of the echo
        double g, r, q;
        void step() {
            g *= r;
            r *= q;
        }
    };
    double q_sigma = -1.0, q_last = 0.0;  // exp(-b^2 / sigma^2) of the last width: slices share one
    auto recurrence = [&](std::size_t i) {
        const Echo& e = echoes[i];
        const PulseShape& shape = shapes[i];
        const double te = e.range_m * to_time;
        const double lo = (te - kWindowSigmas * shape.sigma_s - t0_s) / bin_s_;
        const double hi = (te + kWindowSigmas * shape.sigma_s - t0_s) / bin_s_;
        Recurrence c;
        c.k0 = static_cast<std::size_t>(std::max(0.0, std::floor(lo)));
        c.k1 = std::min(bins - 1, static_cast<std::size_t>(std::max(0.0, std::ceil(hi))));
        const double t = t0_s + static_cast<double>(c.k0) * bin_s_ - te;
        const double inv_var = 1.0 / (shape.sigma_s * shape.sigma_s);
        c.g = e.energy_j * shape.at(t);
        c.r = std::exp(-(2.0 * t * bin_s_ + bin_s_ * bin_s_) * 0.5 * inv_var);
        if (shape.sigma_s != q_sigma) {
            q_sigma = shape.sigma_s;
            q_last = std::exp(-bin_s_ * bin_s_ * inv_var);
        }
        c.q = q_last;
        return c;
    };
    // Two echoes at a time: their recurrences are independent chains of multiplications, and each
    // bin still adds the first echo's term before the second's (the sum is the same to the bit).
    std::size_t i = 0;
    for (; i + 1 < echoes.size(); i += 2) {
        Recurrence a = recurrence(i), b = recurrence(i + 1);
        for (std::size_t k = std::min(a.k0, b.k0); k <= std::max(a.k1, b.k1); ++k) {
            if (k >= a.k0 && k <= a.k1) {
                power[k] += a.g;
                a.step();
            }
            if (k >= b.k0 && k <= b.k1) {
                power[k] += b.g;
                b.step();
            }
        }
    }
    if (i < echoes.size()) {
        Recurrence a = recurrence(i);
        for (std::size_t k = a.k0; k <= a.k1; ++k) {
            power[k] += a.g;
            a.step();
        }
    }
}

DetectedPulse WaveformReceiver::measure(const Window& w, std::size_t peak, std::size_t searched_to) const {
    const double to_time = 2.0 / kSpeedOfLight_mps;
    const double amps_per_watt = apd_.amps_per_watt();
    const double saturation = apd_.saturation_a();
    const double floor_noise = apd_.noise_floor_a();
    // The sampled maximum misses the true peak by up to half a bin (1 % in height for a 1 ns
    // pulse); a parabola through the logarithms of the three samples about it is exact for a
    // Gaussian pulse.
    double offset = 0.0, peak_value = w.y[peak];
    if (peak > 0 && peak + 1 < w.bins && w.y[peak - 1] > 0.0 && w.y[peak + 1] > 0.0 && w.y[peak] < saturation) {
        const double a = std::log(w.y[peak - 1]), b = std::log(w.y[peak]), c = std::log(w.y[peak + 1]);
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
    while (k > searched_to && w.y[k - 1] >= level) --k;
    double t_cross;
    if (k == searched_to) {
        t_cross = w.t0_s + static_cast<double>(k) * bin_s_;
    } else {
        const double f = (level - w.y[k - 1]) / (w.y[k] - w.y[k - 1]);
        t_cross = w.t0_s + (static_cast<double>(k - 1) + f) * bin_s_;
    }
    const double t_peak = w.t0_s + (static_cast<double>(peak) + offset) * bin_s_;
    // Which surface made it: the one whose echo sets the range, i.e. the largest noise-free
    // contribution at the 50 % crossing the range is timed from (a narrow pulse on another
    // surface's broad pedestal is timed from the pedestal's edge when that edge crosses first).
    // Where no echo reaches the crossing (noise), the largest at the peak.
    auto strongest_at = [&](double t) {
        std::fill(w.contribution.begin(), w.contribution.end(), 0.0);
        for (std::size_t j = 0; j < w.echoes.size(); ++j)
            w.contribution[w.echoes[j].surface] += w.echoes[j].energy_j * w.shapes[j].at(t - w.echoes[j].range_m * to_time);
        std::uint32_t strongest = kNoSurface;
        double best = 0.0;
        for (std::uint32_t i = 0; i < w.surfaces; ++i) {
            if (w.contribution[i] > best) {
                best = w.contribution[i];
                strongest = i;
            }
        }
        return strongest;
    };
    std::uint32_t surface = strongest_at(t_cross);
    if (surface == kNoSurface) surface = strongest_at(t_peak);
    const double signal = amps_per_watt * w.power[peak];
    // A peak the echoes barely touch is the noise's, not theirs.
    if (signal < floor_noise) surface = kNoSurface;
    DetectedPulse p;
    p.range_m = 0.5 * kSpeedOfLight_mps * (t_cross + 0.5 * fwhm_s_);
    p.peak_a = peak_value;
    p.snr = surface == kNoSurface ? peak_value / floor_noise : signal / apd_.noise_a(w.power[peak]);
    p.saturated = w.y[peak] >= saturation;
    p.surface = surface;
    return p;
}

}  // namespace ladarsim::sensor_model
