// The receiver's noise, threshold and false-alarm rate against independent computations.
#include <catch2/catch.hpp>

#include <cmath>

#include "ladarsim/sensor_model/signal/apd_receiver.h"
#include "ladarsim/sensor_model/sensor/sensor.h"
#include "ladarsim/sensor_model/signal/waveform.h"

using namespace ladarsim::sensor_model;

TEST_CASE("noise current adds shot, dark and thermal variances", "[apd_receiver]") {
    Sensor c = sensor_preset("paper_ladar");
    const ApdReceiver apd(c.receiver, 0.0);
    // By hand with q = 1.602e-19 C, k = 1.381e-23 J/K:
    //   thermal: 4 k T B / R_L = 4 * 1.381e-23 * 300 * 5e8 / 5000 = 1.6568e-15 A^2
    //   dark:    2 q B M^2 F I_d = 2 * 1.602e-19 * 5e8 * 100 * 5.5 * 5e-9 = 4.4060e-16 A^2
    CHECK(apd.noise_floor_a() == Approx(std::sqrt(1.6568e-15 + 4.4060e-16)).epsilon(1e-3));
    //   with 1 uW of signal: 2 q B M^2 F R0 P = 2 * 1.602e-19 * 5e8 * 100 * 5.5 * 0.9e-6 = 7.9309e-14 A^2
    CHECK(apd.noise_a(1e-6) == Approx(std::sqrt(1.6568e-15 + 4.4060e-16 + 7.9309e-14)).epsilon(1e-3));
}

TEST_CASE("the threshold gives the target false-alarm rate: TNR 5.5 for 1e-3 per 13.3 us gate", "[apd_receiver]") {
    // physics.md: TNR ~ 5.5 gives about 1e-3 false alarms per 13.3 us range gate at B = 500 MHz.
    const double tnr = threshold_to_noise_for(1e-3 / 13.3e-6, 500e6);
    CHECK(tnr == Approx(5.5).margin(0.05));
    CHECK(rice_false_alarm_rate_hz(tnr, 500e6) == Approx(1e-3 / 13.3e-6).epsilon(1e-9));
}

TEST_CASE("band-limited noise crosses a threshold at the Rice rate", "[apd_receiver][waveform]") {
    // An independent check of the formula the threshold comes from: count the upward crossings
    // of the simulated detector noise. At TNR 2.5 the Rice rate is 2.89e8 * exp(-3.125) = 1.27e7 /s,
    // about 1600 crossings in 2^20 samples of 0.125 ns.
    Sensor c = sensor_preset("paper_ladar");
    const ApdReceiver apd(c.receiver, 0.0);
    const WaveformReceiver receiver(apd, 1e-9);
    RandomSequence rng(42, RandomStream::waveform_noise, 0, 0);
    const std::size_t n = std::size_t{1} << 20;
    const std::vector<double> noise = receiver.band_limited_noise(n, rng);
    double mean = 0.0, square = 0.0;
    for (double v : noise) {
        mean += v;
        square += v * v;
    }
    mean /= n;
    CHECK(std::abs(mean) < 0.02);
    CHECK(std::sqrt(square / n) == Approx(1.0).epsilon(0.02));
    const double tnr = 2.5;
    int crossings = 0;
    for (std::size_t i = 1; i < n; ++i) crossings += noise[i - 1] <= tnr && noise[i] > tnr;
    const double seconds = n * receiver.bin_s();
    CHECK(crossings / seconds == Approx(rice_false_alarm_rate_hz(tnr, c.receiver.bandwidth_hz)).epsilon(0.10));
}

TEST_CASE("Gaussian pulse shape: unit energy, FWHM, 10-90 % rise time", "[apd_receiver]") {
    const PulseShape p = PulseShape::of(1e-9);
    double integral = 0.0;
    for (int k = -4000; k <= 4000; ++k) integral += p.at(k * 1e-12) * 1e-12;
    CHECK(integral == Approx(1.0).epsilon(1e-9));
    CHECK(p.at(0.5e-9) == Approx(0.5 * p.peak_per_joule()).epsilon(1e-12));
    // Rise time found by bisection on the shape itself.
    auto time_at = [&](double fraction) {
        double lo = -5e-9, hi = 0.0;
        for (int i = 0; i < 200; ++i) {
            const double mid = 0.5 * (lo + hi);
            (p.at(mid) < fraction * p.peak_per_joule() ? lo : hi) = mid;
        }
        return lo;
    };
    CHECK(p.rise_time_s() == Approx(time_at(0.9) - time_at(0.1)).epsilon(1e-9));
    // Stretching by a spread adds variances.
    CHECK(PulseShape::of(1e-9, 3e-9).sigma_s == Approx(std::hypot(p.sigma_s, 3e-9)));
}
