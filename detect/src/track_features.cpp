#include "ladarsim/detect/track_features.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

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

// Above this the return count's flicker is a wingbeat (a bird's are 2-15 Hz), below it is the
// track's own slower course: a weave of seconds, a turn towards the beam.
constexpr double kHighFlicker_hz = 2.0;

// The residuals of x about its least-squares line in t: what fluctuates, less a steady drift (a
// target approaching grows its count; one descending lowers its height).
std::vector<double> detrended(const std::vector<double>& t, const std::vector<double>& x) {
    if (x.size() < 2) return std::vector<double>(x.size(), 0.0);
    Moments mt, mx;
    double stx = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) mt.add(t[i]), mx.add(x[i]), stx += t[i] * x[i];
    const double var_t = mt.sum2 / mt.n - mt.mean() * mt.mean();
    const double slope = var_t > 0.0 ? (stx / mt.n - mt.mean() * mx.mean()) / var_t : 0.0;
    std::vector<double> out;
    for (std::size_t i = 0; i < x.size(); ++i) out.push_back(x[i] - mx.mean() - slope * (t[i] - mt.mean()));
    return out;
}

double rms(const std::vector<double>& x) {
    double sum2 = 0.0;
    for (double v : x) sum2 += v * v;
    return x.empty() ? 0.0 : std::sqrt(sum2 / static_cast<double>(x.size()));
}

struct Flicker {
    double peak_hz = 0.0, peak_fraction = 0.0, high_fraction = 0.0;
};

// The periodogram of x (detrended, on a regular clock of period_s).
Flicker flicker(const std::vector<double>& x, double period_s) {
    Flicker out;
    const std::size_t n = x.size();
    if (n < kMinFlickerFrames || !(period_s > 0.0)) return out;
    double total = 0.0, peak = 0.0, high = 0.0;
    std::size_t peak_bin = 0;
    for (std::size_t k = 1; k <= n / 2; ++k) {
        std::complex<double> sum = 0.0;
        for (std::size_t i = 0; i < n; ++i)
            sum += x[i] * std::polar(1.0, -2.0 * std::numbers::pi * static_cast<double>(k * i) / static_cast<double>(n));
        const double p = std::norm(sum);
        const double hz = static_cast<double>(k) / (static_cast<double>(n) * period_s);
        total += p;
        if (hz >= kHighFlicker_hz) high += p;
        if (p > peak) peak = p, peak_bin = k;
    }
    // A steady count (to rounding) has no spectrum to speak of.
    if (total <= 1e-9 * static_cast<double>(n)) return out;
    out.peak_hz = static_cast<double>(peak_bin) / (static_cast<double>(n) * period_s);
    out.peak_fraction = peak / total;
    out.high_fraction = high / total;
    return out;
}

}  // namespace

const std::array<std::string_view, kTrackFeatureCount>& track_feature_names() {
    static const std::array<std::string_view, kTrackFeatureCount> names = {
        "speed_mps", "speed_sd_mps", "accel_mps2", "turn_rate_dps", "climb_rate_mps", "altitude_sd_m",
        "extent_m", "extent_sd_m", "returns", "returns_noise", "flicker_hz", "flicker_peak_fraction",
        "flicker_high_fraction", "returns_range2", "frames_seen"};
    return names;
}

TrackFeatures track_features(const std::vector<TrackSample>& all_samples) {
    TrackFeatures f{};
    // The latest frames only: a track is described by what it does now, alike after 3 s or 30 s.
    const std::size_t n = std::min(all_samples.size(), kTrackFeatureFrames);
    const std::vector<TrackSample> samples(all_samples.end() - static_cast<std::ptrdiff_t>(n), all_samples.end());
    std::vector<const TrackSample*> seen;
    for (const TrackSample& s : samples)
        if (!s.predicted) seen.push_back(&s);
    Moments speed, accel, turn, climb, extent, returns, range;
    std::vector<double> seen_time, height;
    for (const TrackSample* s : seen) {
        seen_time.push_back(s->time_s);
        height.push_back(s->centre.z());
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
    // The count over every frame of the window on the frames' own clock (a predicted frame
    // given the mean), its drift taken off.
    std::vector<double> time, count;
    for (const TrackSample& s : samples) {
        time.push_back(s.time_s);
        count.push_back(s.predicted ? returns.mean() : static_cast<double>(s.points));
    }
    const double period_s = n > 1 ? (samples.back().time_s - samples.front().time_s) / static_cast<double>(n - 1) : 0.0;
    const std::vector<double> fluctuation = detrended(time, count);
    const Flicker flick = flicker(fluctuation, period_s);
    const double range_km = range.mean() / 1000.0;
    const double values[kTrackFeatureCount] = {speed.mean(), speed.sd(), accel.mean(), turn.mean(), climb.mean(),
                                               rms(detrended(seen_time, height)), extent.mean(), extent.sd(), returns.mean(),
                                               returns.mean() > 0.0 ? rms(fluctuation) / std::sqrt(returns.mean()) : 0.0, flick.peak_hz,
                                               flick.peak_fraction, flick.high_fraction, returns.mean() * range_km * range_km, static_cast<double>(seen.size())};
    for (std::size_t i = 0; i < kTrackFeatureCount; ++i) f[i] = static_cast<float>(values[i]);
    return f;
}

}  // namespace ladarsim::detect
