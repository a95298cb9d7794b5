#pragma once
// The received waveform of a beam that meets more than one surface: every sub-ray echo adds the
// pulse shape at its time of flight on a fine time grid, band-limited detector noise is added,
// and peaks are found the way the sensor's discriminator would.
#include <cstdint>
#include <cmath>
#include <numbers>
#include <span>
#include <memory>
#include <vector>

#include "ladarsim/dataset/waveform_file.h"
#include "ladarsim/sensor_model/signal/apd_receiver.h"
#include "ladarsim/sensor_model/signal/counter_random.h"

namespace ladarsim::sensor_model {

/// One sub-ray's echo as the receiver times it.
struct Echo {
    double range_m;          ///< as the receiver's clock sees it (folded when ranges fold)
    double energy_j;         ///< optical energy reaching the detector
    std::uint32_t surface;   ///< which surface of the beam it came from
    /// Standard deviation along the range of a distributed echo (a fog or cloud return, or a patch
    /// of surface integrated whole), 0 for a sub-ray's: the pulse it makes is stretched accordingly.
    double spread_m = 0.0;
};

inline constexpr std::uint32_t kNoSurface = 0xFFFFFFFFu;

/// A peak the discriminator reported.
struct DetectedPulse {
    double range_m;          ///< centre of the pulse, from its 50 % leading-edge crossing
    double peak_a;           ///< measured peak current (noise included, clipped at saturation)
    double snr;              ///< noise-free signal current at the peak over the noise there
    bool saturated;
    /// The surface whose echo sets the range: the one contributing most signal at the 50 %
    /// crossing the range is timed from (at the peak where none reaches the crossing); kNoSurface
    /// for noise.
    std::uint32_t surface;
};

class WaveformReceiver {
public:
    /// `bin_s`: the time grid (0.125 ns by default, 1.9 cm of range).
    WaveformReceiver(const ApdReceiver& apd, double pulse_fwhm_s, double bin_s = 0.125e-9);

    /// Detects the pulses in the waveform the echoes make. Echoes more than a few pulse widths
    /// apart get separate windows (the receiver's noise elsewhere is the false-alarm process).
    /// `noise` null: the noise-free waveform; else a window's noise is a stretch of a long
    /// realisation synthesised once, starting where `noise` says (an FFT per window cost more than
    /// everything else a beam does; two windows of a few hundred samples overlap with probability
    /// below 1 %).
    std::vector<DetectedPulse> detect(std::span<const Echo> echoes, RandomSequence* noise) const;
    /// The same, appending to `out` (per-thread scratch buffers: no allocation once warm), and
    /// with `windows` set each window's sampled current (start_s and samples_a) appended to it:
    /// the waveform the pulses were found in, sample for sample.
    void detect(std::span<const Echo> echoes, RandomSequence* noise, std::vector<DetectedPulse>& out,
                std::vector<WaveformWindow>* windows = nullptr) const;

    /// `n` samples of zero-mean, unit-variance Gaussian noise whose spectrum is flat up to the
    /// receiver's bandwidth and zero above (spectral synthesis with one inverse FFT).
    std::vector<double> band_limited_noise(std::size_t n, RandomSequence& rng) const;

    double bin_s() const { return bin_s_; }
    /// Where a pulse's excursion ends: half the threshold (hysteresis, so that noise on a slow
    /// edge, such as a cloud's, does not re-trigger at every wiggle).
    double release_a() const { return 0.5 * apd_.threshold_a(); }
    const PulseShape& pulse() const { return pulse_; }
    /// How much earlier than its centre detect() times one Gaussian pulse of this width (noise
    /// off): its 50 % leading edge, sqrt(2 ln 2) sigma before the centre, plus half the
    /// transmitted FWHM, so sqrt(2 ln 2) (sigma - sigma_transmitted); 0 for the transmitted pulse.
    double timing_offset_s(const PulseShape& shape) const { return std::sqrt(2.0 * std::numbers::ln2) * (shape.sigma_s - pulse_.sigma_s); }

private:
    /// A stretch of a window where pulses can be detected: its bins and the echoes reaching it.
    struct LiveSpan {
        std::size_t first_bin, bins;
        std::size_t first_echo, echoes;
    };
    /// The stretches of a window of `bins` bins from `t0_s` (echoes sorted by range) where the
    /// signal can cross the threshold.
    std::vector<LiveSpan> live_spans(std::span<const Echo> echoes, double t0_s, std::size_t bins, bool noisy) const;
    /// The most the waveform's current can reach with `power_w` of signal: the signal plus two
    /// noise sigmas when noisy (a pulse needs more than the threshold to be detected).
    double reach_a(double power_w, bool noisy) const;
    PulseShape shape_of(const Echo& e) const;
    void detect_window(std::span<const Echo> echoes, double t0_s, std::size_t bins, RandomSequence* noise,
                       std::vector<DetectedPulse>& out, std::vector<WaveformWindow>* windows) const;
    /// One window's sampled waveform and what made it (defined in the .cpp).
    struct Window;
    /// The noise-free power the echoes put in each bin (`power`, of `bins`).
    void sum_pulses(std::span<const Echo> echoes, std::span<const PulseShape> shapes, double t0_s, std::size_t bins,
                    std::vector<double>& power) const;
    /// The pulse whose maximum sample is `peak`: its range (the 50 % leading-edge crossing, searched
    /// back no further than `searched_to`), peak, SNR and the surface that made it.
    DetectedPulse measure(const Window& w, std::size_t peak, std::size_t searched_to) const;

    const ApdReceiver& apd_;
    PulseShape pulse_;
    double fwhm_s_;
    double bin_s_;
    /// Shared by every receiver of the same bandwidth and sampling in the process (drawn from a
    /// fixed stream): a run builds two receivers, a campaign hundreds, and drawing it took half the
    /// time of a one-frame run.
    std::shared_ptr<const std::vector<double>> noise_bank_;
};

}  // namespace ladarsim::sensor_model
