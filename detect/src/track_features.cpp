#include "ladarsim/detect/track_features.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

namespace ladarsim::detect {
namespace {

struct Moments {
    double sum = 0.0, sum2 = 0.0;
    int n = 0;
    void add(double x) {
        sum += x;
        sum2 += x * x;
        ++n;
    }
    double mean() const { return n > 0 ? sum / n : 0.0; }
    double sd() const { return n > 1 ? std::sqrt(std::max(0.0, sum2 / n - mean() * mean())) : 0.0; }
};

constexpr std::size_t kFlickerFrames = 64;
constexpr std::size_t kMinFlickerFrames = 8;

}  // namespace

const std::array<std::string_view, kTrackFeatureCount>& track_feature_names() {
    static const std::array<std::string_view, kTrackFeatureCount> names = {
        "speed_mps", "speed_sd_mps", "accel_mps2", "turn_rate_dps", "climb_rate_mps", "altitude_sd_m", "extent_m", "extent_sd_m",
        "returns", "returns_cv", "flicker_hz", "flicker_peak_fraction", "range_m", "returns_range2", "frames_seen"};
    return names;
}

TrackFeatures track_features(const std::vector<TrackSample>& samples) {
    TrackFeatures f{};
    std::vector<const TrackSample*> seen;
    for (const TrackSample& s : samples)
        if (!s.predicted) seen.push_back(&s);
    Moments speed, accel, turn, climb, altitude, extent, returns, range;
    for (const TrackSample* s : seen) {
        altitude.add(s->centre.z());
        extent.add(s->size.maxCoeff());
        returns.add(static_cast<double>(s->points));
        range.add(s->centre.norm());
    }
    std::vector<Eigen::Vector3d> velocity;
    std::vector<double> velocity_time;
    for (std::size_t i = 1; i < seen.size(); ++i) {
        const double dt = seen[i]->time_s - seen[i - 1]->time_s;
        if (!(dt > 0.0)) continue;
        const Eigen::Vector3d v = (seen[i]->centre - seen[i - 1]->centre) / dt;
        velocity.push_back(v);
        velocity_time.push_back(0.5 * (seen[i]->time_s + seen[i - 1]->time_s));
        speed.add(v.norm());
        climb.add(std::abs(v.z()));
    }
    for (std::size_t i = 1; i < velocity.size(); ++i) {
        const double dt = velocity_time[i] - velocity_time[i - 1];
        if (!(dt > 0.0)) continue;
        accel.add((velocity[i] - velocity[i - 1]).norm() / dt);
        const double norms = velocity[i].norm() * velocity[i - 1].norm();
        if (norms > 0.0) {
            const double c = std::clamp(velocity[i].dot(velocity[i - 1]) / norms, -1.0, 1.0);
            turn.add(std::acos(c) * 180.0 / std::numbers::pi / dt);
        }
    }
    // The count's flicker over the latest frames, on the frames' own clock.
    const std::size_t n = std::min(samples.size(), kFlickerFrames);
    double flicker_hz = 0.0, peak_fraction = 0.0;
    if (n >= kMinFlickerFrames) {
        const auto first = samples.end() - static_cast<std::ptrdiff_t>(n);
        const double period_s = ((first + static_cast<std::ptrdiff_t>(n) - 1)->time_s - first->time_s) / static_cast<double>(n - 1);
        std::vector<double> x;
        for (auto s = first; s != samples.end(); ++s) x.push_back(s->predicted ? returns.mean() : static_cast<double>(s->points));
        double mean = 0.0;
        for (double v : x) mean += v / static_cast<double>(n);
        double total = 0.0, peak = 0.0;
        std::size_t peak_bin = 0;
        for (std::size_t k = 1; k <= n / 2; ++k) {
            std::complex<double> sum = 0.0;
            for (std::size_t i = 0; i < n; ++i)
                sum += (x[i] - mean) * std::polar(1.0, -2.0 * std::numbers::pi * static_cast<double>(k * i) / static_cast<double>(n));
            const double p = std::norm(sum);
            total += p;
            if (p > peak) peak = p, peak_bin = k;
        }
        if (total > 0.0 && period_s > 0.0) {
            flicker_hz = static_cast<double>(peak_bin) / (static_cast<double>(n) * period_s);
            peak_fraction = peak / total;
        }
    }
    const double range_km = range.mean() / 1000.0;
    const double values[kTrackFeatureCount] = {speed.mean(), speed.sd(), accel.mean(), turn.mean(), climb.mean(), altitude.sd(),
                                               extent.mean(), extent.sd(), returns.mean(),
                                               returns.mean() > 0.0 ? returns.sd() / returns.mean() : 0.0, flicker_hz, peak_fraction,
                                               range.mean(), returns.mean() * range_km * range_km, static_cast<double>(seen.size())};
    for (std::size_t i = 0; i < kTrackFeatureCount; ++i) f[i] = static_cast<float>(values[i]);
    return f;
}

}  // namespace ladarsim::detect
