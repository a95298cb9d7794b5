// Track features against tracks whose motion and flicker are known in closed form.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "ladarsim/detect/track_features.h"

using namespace ladarsim::detect;

namespace {

std::size_t index_of(std::string_view name) {
    const auto& names = track_feature_names();
    for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i] == name) return i;
    FAIL("no feature " << name);
    return 0;
}

double feature(const TrackFeatures& f, std::string_view name) { return f[index_of(name)]; }

}  // namespace

TEST_CASE("a straight, level track at constant speed: its speed, no acceleration, turn or climb", "[track_features]") {
    std::vector<TrackSample> samples;
    for (int i = 0; i < 40; ++i) {
        TrackSample s;
        s.time_s = 0.05 * i;
        s.centre = {500.0 - 6.0 * s.time_s, 2.0, 30.0};
        s.size = {0.3, 0.3, 0.1};
        s.points = 12;
        samples.push_back(s);
    }
    const TrackFeatures f = track_features(samples);
    CHECK(feature(f, "speed_mps") == Approx(6.0).epsilon(1e-4));
    CHECK(feature(f, "speed_sd_mps") == Approx(0.0).margin(1e-3));
    CHECK(feature(f, "accel_mps2") == Approx(0.0).margin(1e-2));
    CHECK(feature(f, "turn_rate_dps") == Approx(0.0).margin(0.05));
    CHECK(feature(f, "climb_rate_mps") == Approx(0.0).margin(1e-4));
    CHECK(feature(f, "extent_m") == Approx(0.3).epsilon(1e-5));
    CHECK(feature(f, "returns") == Approx(12.0));
    CHECK(feature(f, "returns_noise") == Approx(0.0).margin(1e-6));
    CHECK(feature(f, "frames_seen") == Approx(40.0));
}

TEST_CASE("a circling track: its turn rate and centripetal acceleration", "[track_features]") {
    std::vector<TrackSample> samples;
    const double radius = 10.0, omega = 0.5;  // rad/s: 28.6 deg/s, 5 m/s, 2.5 m/s^2
    for (int i = 0; i < 60; ++i) {
        TrackSample s;
        s.time_s = 0.05 * i;
        s.centre = {300.0 + radius * std::cos(omega * s.time_s), radius * std::sin(omega * s.time_s), 20.0};
        s.points = 5;
        samples.push_back(s);
    }
    const TrackFeatures f = track_features(samples);
    CHECK(feature(f, "turn_rate_dps") == Approx(omega * 180.0 / M_PI).epsilon(1e-3));
    CHECK(feature(f, "speed_mps") == Approx(radius * omega).epsilon(1e-3));
    CHECK(feature(f, "accel_mps2") == Approx(radius * omega * omega).epsilon(1e-2));
}

TEST_CASE("a return count beating at 6 Hz in 20 Hz frames: flicker at 6 Hz with most of the power", "[track_features]") {
    std::vector<TrackSample> samples;
    for (int i = 0; i < 64; ++i) {
        TrackSample s;
        s.time_s = 0.05 * i;
        s.centre = {150.0, 0.0, 10.0};
        s.points = static_cast<std::size_t>(std::lround(20.0 + 8.0 * std::sin(2.0 * M_PI * 6.0 * s.time_s)));
        samples.push_back(s);
    }
    const TrackFeatures f = track_features(samples);
    // Bins are 20 / 64 = 0.31 Hz apart.
    CHECK(feature(f, "flicker_hz") == Approx(6.0).margin(0.32));
    CHECK(feature(f, "flicker_peak_fraction") > 0.5);
    // 8 / sqrt(2) RMS about 20: 1.26 times counting noise's sqrt(20).
    CHECK(feature(f, "returns_noise") == Approx(8.0 / std::sqrt(2.0) / std::sqrt(20.0)).epsilon(0.05));
    // A steady count has no flicker.
    for (auto& s : samples) s.points = 20;
    CHECK(feature(track_features(samples), "flicker_peak_fraction") == 0.0f);
}

TEST_CASE("predicted frames count for the flicker's clock but not for motion", "[track_features]") {
    std::vector<TrackSample> samples;
    for (int i = 0; i < 10; ++i) {
        TrackSample s;
        s.time_s = 0.1 * i;
        s.centre = {100.0 + 2.0 * s.time_s, 0, 0};
        s.points = 3;
        s.predicted = i % 3 == 1;
        if (s.predicted) s.centre.x() += 50.0;  // where a prediction went wrong: ignored
        samples.push_back(s);
    }
    const TrackFeatures f = track_features(samples);
    CHECK(feature(f, "speed_mps") == Approx(2.0).epsilon(1e-4));
    CHECK(feature(f, "frames_seen") == Approx(7.0));
}

TEST_CASE("a steady climb is no bobbing, a wing's flicker is high and a slow weave's is not", "[track_features]") {
    std::vector<TrackSample> samples;
    for (int i = 0; i < 64; ++i) {
        TrackSample s;
        s.time_s = 0.05 * i;
        // Descending 0.3 m/s towards the sensor, as a drone approaching from above does.
        s.centre = {450.0 - 6.0 * s.time_s, 0.0, 27.0 - 0.3 * s.time_s};
        // Its count growing as it nears, with a 0.4 Hz weave.
        s.points = static_cast<std::size_t>(std::lround(40.0 + 3.0 * s.time_s + 6.0 * std::sin(2.0 * M_PI * 0.4 * s.time_s)));
        samples.push_back(s);
    }
    TrackFeatures f = track_features(samples);
    CHECK(feature(f, "climb_rate_mps") == Approx(0.3).epsilon(1e-3));
    CHECK(feature(f, "altitude_sd_m") == Approx(0.0).margin(1e-4));
    CHECK(feature(f, "flicker_high_fraction") < 0.1);
    // Bobbing 5 cm at 6 Hz with the wing, and the count beating with it.
    for (auto& s : samples) {
        s.centre.z() += 0.05 * std::sin(2.0 * M_PI * 6.0 * s.time_s);
        s.points += static_cast<std::size_t>(std::lround(8.0 + 8.0 * std::sin(2.0 * M_PI * 6.0 * s.time_s)));
    }
    f = track_features(samples);
    CHECK(feature(f, "altitude_sd_m") == Approx(0.05 / std::sqrt(2.0)).epsilon(0.1));
    CHECK(feature(f, "flicker_high_fraction") > 0.5);
}

TEST_CASE("a track's features come from its latest 64 frames", "[track_features]") {
    std::vector<TrackSample> samples;
    for (int i = 0; i < 200; ++i) {
        TrackSample s;
        s.time_s = 0.05 * i;
        // 2 m/s for 136 frames, then 8 m/s.
        s.centre = {i < 136 ? 2.0 * s.time_s : 2.0 * 6.8 + 8.0 * (s.time_s - 6.8), 0.0, 30.0};
        s.points = i < 136 ? 5 : 30;
        samples.push_back(s);
    }
    const TrackFeatures f = track_features(samples);
    CHECK(feature(f, "speed_mps") == Approx(8.0).epsilon(1e-3));
    CHECK(feature(f, "returns") == Approx(30.0));
    CHECK(feature(f, "frames_seen") == Approx(static_cast<double>(kTrackFeatureFrames)));
}
