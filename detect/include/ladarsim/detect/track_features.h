#pragma once
// What a tracker sees of one track over time, as the numbers a classifier of birds, drones,
// aircraft and clutter reads: how it moves, how big it looks, and how its return count flickers
// (a beating wing shows as a peak in that count's spectrum).
#include <array>
#include <cstddef>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace ladarsim::detect {

/// One frame of a track (sensor frame: x along the boresight, z up when the sensor is level).
struct TrackSample {
    double time_s = 0.0;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< box extent
    std::size_t points = 0;                          ///< returns; 0 when predicted
    bool predicted = false;                          ///< no cluster this frame
};

inline constexpr std::size_t kTrackFeatureCount = 15;
using TrackFeatures = std::array<float, kTrackFeatureCount>;

/// The frames a track's features look back over: its latest 3.2 s at 20 Hz.
inline constexpr std::size_t kTrackFeatureFrames = 64;

/// The fewest frames (seen or predicted) whose return count has a periodogram: with fewer the
/// flicker features are 0.
inline constexpr std::size_t kMinFlickerFrames = 8;

/// The features' names, in order: speed_mps, speed_sd_mps, accel_mps2, turn_rate_dps,
/// climb_rate_mps, altitude_sd_m, extent_m, extent_sd_m, returns, returns_noise, flicker_hz,
/// flicker_peak_fraction, flicker_high_fraction, returns_range2, frames_seen. Range is not one: a
/// model given it learns the training scenes' distances (one called a drone at 2 km a plane, the
/// aircraft it was trained on being that far).
const std::array<std::string_view, kTrackFeatureCount>& track_feature_names();

/// The features of a track from its latest kTrackFeatureFrames samples, in time order (at least
/// one). Motion comes from frames with a cluster only; with fewer than two, or three for
/// acceleration and turn rate, those features are 0. altitude_sd_m is the height's spread about
/// its straight-line trend (bobbing, not a steady climb). The return count, predicted frames given
/// the mean, less its straight-line trend, is what fluctuates: returns_noise is its RMS over the
/// square root of the mean, the spread counting alone gives (1 for Poisson counts), so that a far
/// target's few returns, which fluctuate more for their number, do not read as a wing's beat (over
/// the mean it was 0.1 for a drone at 1.9 km and for birds at 500 m); flicker_hz the frequency of
/// its periodogram's largest peak, flicker_peak_fraction that peak's share of the power and
/// flicker_high_fraction the share at 2 Hz and above, where a beating wing shows (all 0 with under
/// kMinFlickerFrames frames or a steady count). returns_range2 is the mean count times the range
/// squared (km^2): what the count would be at 1 km for a target filling fewer beams than its
/// footprint, a size that does not fall with range. frames_seen counts the frames with a cluster.
TrackFeatures track_features(const std::vector<TrackSample>& samples);

}  // namespace ladarsim::detect
