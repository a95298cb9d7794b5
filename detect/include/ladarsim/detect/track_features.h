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

inline constexpr std::size_t kTrackFeatureCount = 16;
using TrackFeatures = std::array<float, kTrackFeatureCount>;

/// The frames a track's features look back over: its latest 3.2 s at 20 Hz.
inline constexpr std::size_t kTrackFeatureFrames = 64;

/// The features' names, in order: speed_mps, speed_sd_mps, accel_mps2, turn_rate_dps,
/// climb_rate_mps, altitude_sd_m, extent_m, extent_sd_m, returns, returns_cv, flicker_hz,
/// flicker_peak_fraction, flicker_high_fraction, range_m, returns_range2, frames_seen.
const std::array<std::string_view, kTrackFeatureCount>& track_feature_names();

/// The features of a track from its latest kTrackFeatureFrames samples, in time order (at least
/// one). Motion comes from frames with a cluster only; with fewer than two, or three for
/// acceleration and turn rate, those features are 0. altitude_sd_m is the height's spread about
/// its straight-line trend (bobbing, not a steady climb). The return count, predicted frames given
/// the mean, less its straight-line trend, is what fluctuates: returns_cv is its RMS over the
/// mean; flicker_hz the frequency of its periodogram's largest peak, flicker_peak_fraction that
/// peak's share of the power and flicker_high_fraction the share at 2 Hz and above, where a
/// beating wing shows (all 0 with under 8 frames or a steady count). returns_range2 is the mean
/// count times the range squared (km^2): what the count would be at 1 km for a target filling
/// fewer beams than its footprint, a size that does not fall with range. frames_seen counts the
/// frames with a cluster.
TrackFeatures track_features(const std::vector<TrackSample>& samples);

}  // namespace ladarsim::detect
