#pragma once
// Every target in the field, not only the cued one: Algorithm 1's background subtraction and
// clustering give the candidates of each frame, and tracks (constant-velocity predictions,
// associated by least total centre distance within a speed gate) follow them.
#include <cstdint>
#include <memory>
#include <vector>

#include "ladarsim/detect/tracker.h"

namespace ladarsim::detect {

/// A confirmed track in one frame.
struct TrackedObject {
    std::uint32_t track = 0;  ///< from 1, in order of birth
    OrientedBox box;          ///< around its cluster's points (or predicted)
    OrientedBox sensor_box;   ///< sensor_aware_box of it
    std::size_t points = 0;   ///< 0 when predicted
    bool predicted = false;   ///< no cluster this frame: where the track's motion puts it
    /// How sure: the cluster's points, halved for every frame in a row the track went unseen
    /// (ranks the hypotheses for average precision).
    double score = 0.0;
};

class MultiTargetTracker {
public:
    /// A track is confirmed by its second cluster in a row and ends after this many frames unseen.
    static constexpr int kConfirmingHits = 2;
    static constexpr int kMaxMisses = 5;

    MultiTargetTracker(const DetectorConfig& config, const SensorGeometry& sensor, const Points& background_map);
    ~MultiTargetTracker();
    MultiTargetTracker(const MultiTargetTracker&) = delete;
    MultiTargetTracker& operator=(const MultiTargetTracker&) = delete;

    /// The confirmed tracks after this frame.
    std::vector<TrackedObject> process(double time_s, const Points& points);

private:
    struct Track;
    DetectorConfig config_;
    SensorGeometry sensor_;
    BackgroundSubtractor background_;
    std::vector<Track> tracks_;
    std::uint32_t next_track_ = 1;
};

}  // namespace ladarsim::detect
