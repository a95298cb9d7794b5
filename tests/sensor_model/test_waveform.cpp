// The waveform receiver: timing jitter against (c/2) t_rise / SNR, merging of close surfaces,
// energies of separate ones.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "ladarsim/sensor_model/signal/beam_receiver.h"
#include "ladarsim/sensor_model/sensor/physical_constants.h"
#include "ladarsim/sensor_model/signal/waveform.h"
#include "../support/atmospheres.h"

using namespace ladarsim::sensor_model;

namespace {

/// Energy on the detector that gives a pulse of amplitude SNR `snr`: solves
/// snr = A/W * E * h / noise(E * h) for E by fixed-point iteration (h the peak per joule).
double energy_for_snr(const ApdReceiver& apd, const PulseShape& pulse, double snr) {
    double power = snr * apd.noise_floor_a() / apd.amps_per_watt();
    for (int i = 0; i < 100; ++i) power = snr * apd.noise_a(power) / apd.amps_per_watt();
    return power / pulse.peak_per_joule();
}

Sensor quiet_sensor() {
    Sensor c = sensor_preset("paper_ladar");
    c.receiver.range_folding = false;
    return c;
}

}  // namespace

TEST_CASE("range jitter of the timed pulse against its first-order closed form", "[waveform]") {
    const Sensor c = quiet_sensor();
    const ApdReceiver apd(c.receiver, 0.0);
    const WaveformReceiver receiver(apd, 1e-9);
    for (double snr : {15.0, 40.0}) {
        const double energy = energy_for_snr(apd, receiver.pulse(), snr);
        const std::vector<Echo> echo = {{1000.0, energy, 0}};
        double sum = 0.0, square = 0.0;
        int count = 0;
        for (std::uint32_t pulse = 0; pulse < 4000; ++pulse) {
            RandomSequence noise(7, RandomStream::waveform_noise, 0, pulse);
            for (const DetectedPulse& p : receiver.detect(echo, &noise)) {
                if (p.surface != 0) continue;
                sum += p.range_m;
                square += p.range_m * p.range_m;
                ++count;
            }
        }
        REQUIRE(count > 3900);
        const double mean = sum / count;
        const double sigma = std::sqrt(square / count - mean * mean);
        INFO("SNR " << snr);
        const double peak_power = energy * receiver.pulse().peak_per_joule();
        CHECK(sigma == Approx(apd.range_jitter_m(peak_power, receiver.pulse())).epsilon(0.10));
        // The textbook (c/2) t_rise / SNR ignores that the crossing level comes from the noisy
        // peak (correlated with the crossing's noise) and that shot noise follows the signal:
        // it over-states this discriminator's jitter by 1.8x here.
        const double textbook = 0.5 * kSpeedOfLight_mps * receiver.pulse().rise_time_s() / snr;
        WARN("SNR " << snr << ": simulated " << sigma * 1e3 << " mm, closed form "
                    << apd.range_jitter_m(peak_power, receiver.pulse()) * 1e3 << " mm, textbook " << textbook * 1e3 << " mm");
        CHECK(sigma < textbook);
        // The 50 % crossing plus half the FWHM finds the pulse centre without bias.
        CHECK(mean == Approx(1000.0).margin(3.0 * sigma / std::sqrt(count) + 1e-3));
    }
}

TEST_CASE("two surfaces 10 cm apart make one return, 50 cm apart two, energies in their ratio", "[waveform]") {
    const Sensor c = quiet_sensor();
    const BeamReceiver receiver(c, ladarsim::test::vacuum(), false);
    const ApdReceiver& apd = receiver.apd();
    const double e1 = energy_for_snr(apd, receiver.waveform().pulse(), 200.0);
    const double e2 = 0.4 * e1;
    auto surfaces = [&](double gap_m) {
        std::vector<BeamSurface> s(2);
        s[0].object_id = 1;
        s[0].weight = 0.6;
        s[0].echoes = {{500.0, e1, 0}};
        s[1].object_id = 2;
        s[1].weight = 0.4;
        s[1].echoes = {{500.0 + gap_m, e2, 0}};
        return s;
    };
    const auto merged = receiver.receive(surfaces(0.10), BeamKey{1, 0, 0});
    REQUIRE(merged.size() == 1);
    CHECK(merged[0].object_id == 1);
    CHECK(merged[0].range_m > 500.0);
    CHECK(merged[0].range_m < 500.1);

    const auto split = receiver.receive(surfaces(0.50), BeamKey{1, 0, 0});
    REQUIRE(split.size() == 2);
    CHECK(split[0].object_id == 1);
    CHECK(split[1].object_id == 2);
    CHECK(split[0].range_m == Approx(500.0).margin(0.005));
    CHECK(split[1].range_m == Approx(500.5).margin(0.005));
    CHECK(split[0].energy_j == Approx(e1).epsilon(0.01));
    CHECK(split[1].energy_j / split[0].energy_j == Approx(0.4).epsilon(0.01));
}

TEST_CASE("the pulse-merging distance is the pulse's own: c tau / 2 = 15 cm", "[waveform]") {
    const Sensor c = quiet_sensor();
    const BeamReceiver receiver(c, ladarsim::test::vacuum(), false);
    const double e = energy_for_snr(receiver.apd(), receiver.waveform().pulse(), 200.0);
    auto returns_at_gap = [&](double gap_m) {
        std::vector<BeamSurface> s(2);
        s[0].echoes = {{300.0, e, 0}};
        s[1].object_id = 1;
        s[1].echoes = {{300.0 + gap_m, e, 0}};
        return receiver.receive(s, BeamKey{1, 0, 0}).size();
    };
    // Two equal Gaussian pulses show a dip between them once they are more than 2 sigma apart
    // (0.85 ns, 12.7 cm); the discriminator splits them when the dip falls below half the peak.
    CHECK(returns_at_gap(0.08) == 1);
    CHECK(returns_at_gap(0.12) == 1);
    CHECK(returns_at_gap(0.25) == 2);
}
