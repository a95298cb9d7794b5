// BeamReceiver: false alarms, detection probability, folding, saturation, hard cases.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "ladarsim/sensor_model/signal/beam_receiver.h"
#include "ladarsim/sensor_model/sensor/physical_constants.h"
#include "../support/atmospheres.h"

using namespace ladarsim;
using namespace ladarsim::sensor_model;

namespace {

BeamSurface one_surface(double range_m, double energy_j, std::uint32_t object_id = 1) {
    BeamSurface s;
    s.object_id = object_id;
    s.weight = 1.0;
    s.echoes = {{range_m, energy_j, 0}};
    return s;
}

}  // namespace

TEST_CASE("false alarms over 1e6 range gates match the Rice rate", "[beam_receiver]") {
    Sensor c = sensor_preset("paper_ladar");
    c.receiver.range_folding = false;
    c.receiver.max_range_m = 2000.0;  // a 13.3 us gate
    const BeamReceiver receiver(c, ladarsim::test::vacuum());
    const int gates = 1'000'000;
    long long alarms = 0;
    for (int g = 0; g < gates; ++g) {
        const auto returns = receiver.receive({}, BeamKey{3, static_cast<std::uint64_t>(g / 3000), static_cast<std::uint32_t>(g % 3000)});
        for (const auto& r : returns) {
            REQUIRE(r.source == ReturnSource::false_alarm);
            REQUIRE(r.object_id == kNoObject);
            REQUIRE(r.range_m >= 0.0);
            REQUIRE(r.range_m <= 2000.0);
        }
        alarms += static_cast<long long>(returns.size());
    }
    // Rice: B / sqrt(3) exp(-TNR^2 / 2) with the threshold set for 75 /s: 1.0e-3 per gate.
    const double gate_s = 2.0 * 2000.0 / kSpeedOfLight_mps;
    const double expected = gates * rice_false_alarm_rate_hz(receiver.apd().threshold_to_noise(), c.receiver.bandwidth_hz) * gate_s;
    CHECK(expected == Approx(1000.6).epsilon(0.01));
    CHECK(static_cast<double>(alarms) == Approx(expected).epsilon(0.10));
}

TEST_CASE("detection probability of a return follows the Gaussian noise at its peak", "[beam_receiver]") {
    Sensor c = sensor_preset("paper_ladar");
    c.receiver.range_folding = false;
    c.receiver.false_alarm_rate_hz = 1e-9;  // count only the surface
    const BeamReceiver receiver(c, ladarsim::test::vacuum());
    const ApdReceiver& apd = receiver.apd();
    const PulseShape pulse = receiver.waveform().pulse();
    // A signal at the threshold plus one noise sigma (the noise with that signal): Pd = Phi(1) = 0.841.
    const double target_power = [&] {
        double p = apd.threshold_a() / apd.amps_per_watt();
        for (int i = 0; i < 100; ++i) p = (apd.threshold_a() + apd.noise_a(p)) / apd.amps_per_watt();
        return p;
    }();
    const double energy = target_power / pulse.peak_per_joule();
    int detected = 0;
    const int beams = 20000;
    for (int b = 0; b < beams; ++b) {
        BeamSurface s = one_surface(1000.0, energy);
        s.source = ReturnSource::volume;  // no speckle: the test is about the detector alone
        detected += static_cast<int>(receiver.receive({s}, BeamKey{5, 0, static_cast<std::uint32_t>(b)}).size());
    }
    CHECK(detected / double(beams) == Approx(0.8413).margin(0.01));
}

TEST_CASE("range folding: returns beyond c / (2 PRF) arrive in a later pulse's gate", "[beam_receiver]") {
    Sensor c = sensor_preset("paper_ladar");  // the paper's 1 MHz: 149.9 m unambiguous range
    const BeamReceiver folding(c, ladarsim::test::vacuum(), false);
    c.receiver.range_folding = false;
    const BeamReceiver coded(c, ladarsim::test::vacuum(), false);
    const double energy = 1e-14;
    const auto folded = folding.receive({one_surface(600.0, energy)}, BeamKey{1, 0, 0});
    const auto plain = coded.receive({one_surface(600.0, energy)}, BeamKey{1, 0, 0});
    REQUIRE(folded.size() == 1);
    REQUIRE(plain.size() == 1);
    const double ambiguity = kSpeedOfLight_mps / 2e6;
    CHECK(folded[0].pulse_offset == 4);
    CHECK(folded[0].range_m == Approx(600.0 - 4 * ambiguity).margin(1e-9));
    CHECK(plain[0].pulse_offset == 0);
    CHECK(plain[0].range_m == Approx(600.0).margin(1e-9));
}

TEST_CASE("a strong near return saturates and never reports more than the pulse", "[beam_receiver]") {
    Sensor c = sensor_preset("paper_ladar");
    c.receiver.range_folding = false;
    const BeamReceiver receiver(c, ladarsim::test::vacuum(), false);
    // A white wall 5 m away would put 7e-9 J on the detector: amps, far past the 2 mA clip.
    const auto r = receiver.receive({one_surface(5.0, 7e-9)}, BeamKey{1, 0, 0});
    REQUIRE(r.size() == 1);
    CHECK(r[0].saturated);
    CHECK(r[0].energy_j < 7e-9);
    CHECK(r[0].energy_j == Approx(c.receiver.saturation_current_a / (receiver.apd().amps_per_watt() *
                                                            receiver.waveform().pulse().peak_per_joule())));
    CHECK(r[0].energy_j < c.transmitter.pulse_energy_j());
}

TEST_CASE("hard cases give finite, sensible numbers: 2 km, grazing stretch, sub-threshold", "[beam_receiver]") {
    Sensor c = sensor_preset("paper_ladar");
    c.receiver.range_folding = false;
    const BeamReceiver receiver(c, ladarsim::test::vacuum());
    // A 0.3 m drone at 2 km holding 6 % of the footprint: about 1e-15 J.
    auto far = receiver.receive({one_surface(2000.0, 2e-15)}, BeamKey{1, 0, 1});
    for (const auto& r : far) {
        CHECK(std::isfinite(r.range_m));
        CHECK(std::isfinite(r.energy_j));
        CHECK(r.snr > 0.0);
    }
    // A grazing surface: 16 echoes spread over 25 m of range make one stretched, weaker pulse.
    BeamSurface grazing;
    grazing.object_id = 2;
    grazing.weight = 1.0;
    for (int i = 0; i < 16; ++i) grazing.echoes.push_back({330.0 + 25.0 * i / 15.0, 1e-13 / 16, 0});
    const auto stretched = receiver.receive({grazing}, BeamKey{1, 0, 2});
    REQUIRE(stretched.size() >= 1);
    for (const auto& r : stretched) {
        if (r.source != ReturnSource::surface) continue;
        CHECK(r.range_m > 330.0);
        CHECK(r.range_m < 355.0);
        CHECK(std::isfinite(r.snr));
    }
    // Nothing but noise below the threshold: at most false alarms, never a surface.
    for (const auto& r : receiver.receive({one_surface(2000.0, 1e-22)}, BeamKey{1, 0, 3}))
        CHECK(r.source == ReturnSource::false_alarm);
}

TEST_CASE("reported returns: all, first, last, strongest, first and last", "[beam_receiver]") {
    Sensor c = sensor_preset("paper_ladar");
    c.receiver.range_folding = false;
    auto receive = [&](ReportedReturns mode) {
        c.receiver.reported_returns = mode;
        const BeamReceiver receiver(c, ladarsim::test::vacuum(), false);
        return receiver.receive({one_surface(100.0, 1e-15, 1), one_surface(101.0, 5e-15, 2), one_surface(102.0, 2e-15, 3)},
                                BeamKey{1, 0, 0});
    };
    CHECK(receive(ReportedReturns::all).size() == 3);
    CHECK(receive(ReportedReturns::first).front().object_id == 1);
    CHECK(receive(ReportedReturns::last).front().object_id == 3);
    CHECK(receive(ReportedReturns::strongest).front().object_id == 2);
    const auto both = receive(ReportedReturns::first_and_last);
    REQUIRE(both.size() == 2);
    CHECK(both[0].object_id == 1);
    CHECK(both[1].object_id == 3);
}

TEST_CASE("echoes the waveform cannot tell apart enter it as one: the returns of every echo alone", "[beam_receiver]") {
    // The receiver merges a surface's echoes whose pulses nearly coincide (centres within a tenth
    // of their width, widths within 2 %). Against the waveform of every echo on its own (computed
    // here directly), on a drone's 400 sub-ray echoes within 0.15 m, a grazing ground's 300 echoes
    // of varying stretch over 5 m, and a surface whose narrow and wide pulses share their centres
    // (a narrow peak on a wide pedestal, which one merged pulse of their mean width would flatten).
    Sensor c = sensor_preset("paper_ladar");
    c.receiver.range_folding = false;
    const BeamReceiver receiver(c, ladarsim::test::vacuum(), false);
    const double threshold_j = receiver.apd().threshold_a() / (receiver.apd().amps_per_watt() * receiver.waveform().pulse().peak_per_joule());
    std::vector<BeamSurface> surfaces(3);
    for (std::uint32_t k = 0; k < 3; ++k) {
        surfaces[k].object_id = k + 1;
        surfaces[k].weight = 1.0 / 3.0;
    }
    for (int i = 0; i < 400; ++i)  // sorted, as gather_surfaces leaves them
        surfaces[0].echoes.push_back({1000.0 + 0.15 * i / 399.0, 40.0 * threshold_j / 400.0 * (1.0 + 0.5 * std::sin(0.37 * i)), 0});
    for (int i = 0; i < 300; ++i)
        surfaces[1].echoes.push_back({1003.0 + 5.0 * i / 299.0, 300.0 * threshold_j / 300.0 * (1.0 + 0.8 * std::sin(0.05 * i)), 0, 0.01 + 0.3 * (i % 7) / 6.0});
    for (int i = 0; i < 40; ++i)
        surfaces[2].echoes.push_back({1012.0 + 0.001 * i, 6.0 * threshold_j / 40.0, 0, i % 2 ? 0.8 : 0.0});
    std::vector<Echo> one_by_one;
    for (std::uint32_t k = 0; k < 3; ++k)
        for (Echo e : surfaces[k].echoes) {
            e.surface = k;
            one_by_one.push_back(e);
        }
    const std::vector<DetectedPulse> expected = receiver.waveform().detect(one_by_one, nullptr);
    const std::vector<DetectedReturn> got = receiver.receive(surfaces, BeamKey{1, 0, 0});
    for (const auto& p : expected) UNSCOPED_INFO(p.range_m << " m, surface " << p.surface << ", peak " << p.peak_a);
    REQUIRE(expected.size() >= 3);
    REQUIRE(got.size() == expected.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
        INFO("return " << i << " at " << expected[i].range_m << " m");
        CHECK(got[i].range_m == Approx(expected[i].range_m).margin(1e-4));
        const double expected_j = expected[i].peak_a / (receiver.apd().amps_per_watt() * receiver.waveform().pulse().peak_per_joule());
        CHECK(got[i].energy_j == Approx(expected_j).epsilon(1e-3));
        CHECK(got[i].object_id == surfaces[expected[i].surface].object_id);
    }
}

TEST_CASE("a recorded map's surface metres deep draws its waveform: one surface or two, the same returns", "[beam_receiver]") {
    // A stadium's stands over a recorded map: four steps a metre apart joined by weak risers, so
    // that grouping by range gaps may make them one surface or two, as a few discs fall. Before,
    // one surface took the closed form (one return at the mean range, of all the energy) and two
    // the waveform (four returns): the first return jumped by 1.5 m on a disc or two.
    Sensor c = sensor_preset("paper_ladar");
    c.receiver.range_folding = false;
    const BeamReceiver receiver(c, ladarsim::test::vacuum(), false);
    const double threshold_j = receiver.apd().threshold_a() / (receiver.apd().amps_per_watt() * receiver.waveform().pulse().peak_per_joule());
    std::vector<Echo> steps;
    for (int step = 0; step < 4; ++step) {
        for (int k = 0; k < 21; ++k) steps.push_back({700.0 + step + 0.003 * (k - 10), 200.0 * threshold_j / 21, 0});
        if (step < 3)
            for (int k = 1; k < 10; ++k) steps.push_back({700.0 + step + 0.1 * k, 0.01 * threshold_j, 0});
    }
    auto surface = [&](std::size_t first, std::size_t last, bool profiled) {
        BeamSurface s;
        s.object_id = 0;
        s.weight = 0.5;
        s.profiled = profiled;
        s.echoes.assign(steps.begin() + static_cast<std::ptrdiff_t>(first), steps.begin() + static_cast<std::ptrdiff_t>(last));
        return s;
    };
    const std::size_t half = 2 * (21 + 9);  // the first two steps and the risers after them
    const auto one = receiver.receive({surface(0, steps.size(), true)}, BeamKey{1, 0, 1});
    const auto two = receiver.receive({surface(0, half, true), surface(half, steps.size(), true)}, BeamKey{1, 0, 1});
    REQUIRE(two.size() == 4);
    REQUIRE(one.size() == two.size());
    for (std::size_t i = 0; i < one.size(); ++i) {
        CHECK(one[i].range_m == Approx(two[i].range_m).margin(1e-3));
        CHECK(one[i].range_m == Approx(700.0 + static_cast<double>(i)).margin(0.01));
        CHECK(one[i].energy_j == Approx(two[i].energy_j).epsilon(1e-3));
    }
    // A patch's surface (its spread carried, not drawn) keeps the closed form: one return.
    CHECK(receiver.receive({surface(0, steps.size(), false)}, BeamKey{1, 0, 1}).size() == 1);
    // So does a weak one, whose closed-form peak is under 10 thresholds (here about 5): which of
    // its steps cross the threshold is what no integration of a map resolves.
    std::vector<Echo> weak = steps;
    for (Echo& e : weak) e.energy_j *= 0.1;
    BeamSurface faint = surface(0, steps.size(), true);
    faint.echoes = weak;
    CHECK(receiver.receive({faint}, BeamKey{1, 0, 1}).size() == 1);
    // Centres within the pulse's sigma make one peak however they lie: the closed form, profiled
    // or not (the first step alone).
    const auto compact = receiver.receive({surface(0, 21, true)}, BeamKey{1, 0, 1});
    const auto patch = receiver.receive({surface(0, 21, false)}, BeamKey{1, 0, 1});
    REQUIRE(compact.size() == 1);
    REQUIRE(patch.size() == 1);
    CHECK(compact[0].range_m == patch[0].range_m);
    CHECK(compact[0].energy_j == patch[0].energy_j);
}

TEST_CASE("one stretched surface: the closed form reports what the waveform's discriminator does", "[beam_receiver]") {
    // Ground grazed over a footprint stretches its pulse. The discriminator times a pulse by its
    // 50 % leading edge plus half the transmitted FWHM and reads its intensity from the peak over
    // the transmitted pulse's peak: for a Gaussian of sigma s (range units) against the pulse's
    // sigma p, sqrt(2 ln 2) (s - p) before its centre and p / s of its energy. One surface takes
    // the closed form, the same surface beside another the waveform: a beam must not report
    // another range because a bird entered its footprint.
    Sensor c = sensor_preset("paper_ladar");
    c.receiver.range_folding = false;
    const BeamReceiver receiver(c, ladarsim::test::vacuum(), false);
    const double peak_per_joule = receiver.waveform().pulse().peak_per_joule();
    const double threshold_j = receiver.apd().threshold_a() / (receiver.apd().amps_per_watt() * peak_per_joule);
    const double p = receiver.waveform().pulse().sigma_s * 0.5 * kSpeedOfLight_mps;
    for (const double spread : {0.0, 0.05, 0.3, 1.2}) {
        INFO("spread " << spread << " m");
        BeamSurface ground;
        ground.object_id = 3;
        ground.weight = 1.0;
        ground.echoes = {{800.0, 200.0 * threshold_j, 0, spread}};
        const double s = std::sqrt(p * p + spread * spread);
        const auto closed = receiver.receive({ground}, BeamKey{1, 0, 1});
        std::vector<BeamSurface> surfaces = {ground};
        std::vector<DetectedReturn> drawn;
        std::vector<WaveformWindow> windows;  // asking for the waveform draws it
        receiver.receive(surfaces, BeamKey{1, 0, 1}, drawn, &windows);
        REQUIRE(closed.size() == 1);
        REQUIRE(drawn.size() == 1);
        CHECK(closed[0].range_m == Approx(800.0 - std::sqrt(2.0 * std::log(2.0)) * (s - p)).margin(1e-9));
        CHECK(closed[0].energy_j / (200.0 * threshold_j) == Approx(p / s).epsilon(1e-9));
        // The waveform's samples every 0.125 ns (19 mm), its peak refined by a log-parabola: mm.
        CHECK(drawn[0].range_m == Approx(closed[0].range_m).margin(2e-3));
        CHECK(drawn[0].energy_j / closed[0].energy_j == Approx(1.0).epsilon(2e-3));
        // A volume's free-path samples keep their mean range and all their energy (too few to
        // place an edge: see closed_form).
        BeamSurface cloud = ground;
        cloud.source = ReturnSource::volume;
        const auto volume = receiver.receive({cloud}, BeamKey{1, 0, 1});
        REQUIRE(volume.size() == 1);
        CHECK(volume[0].range_m == 800.0);
        CHECK(volume[0].energy_j / (200.0 * threshold_j) == Approx(1.0).epsilon(1e-12));
    }
}
