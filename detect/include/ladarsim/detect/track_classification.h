#pragma once
// The tracks of a sequence as a classifier sees them: each track's history, what it follows in
// the ground truth, training rows from rendered sequences, and the class of each track in each
// frame from what it has shown so far.
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladarsim/detect/multi_target.h"
#include "ladarsim/detect/track_classifier.h"
#include "ladarsim/detect/track_features.h"
#include "ladarsim/detect/tracking_metrics.h"

namespace ladarsim::detect {

struct Sequence;

/// One track over the frames it was confirmed in: which frames (indices into the sequence) and
/// what each showed.
struct TrackHistory {
    std::uint32_t track = 0;
    std::vector<std::size_t> frames;
    std::vector<TrackSample> samples;
};

/// The tracks of track_sequence's output, in order of birth.
std::vector<TrackHistory> track_histories(const std::vector<double>& time_s, const std::vector<std::vector<TrackedObject>>& tracked);

/// Centre distance within which a track's box follows a ground-truth object (eval's tracking gate).
inline constexpr double kFollowGate_m = 2.0;

/// What a track follows: the class (index into track_class_names()) of the nearest ground-truth
/// drone, bird or aircraft within kFollowGate_m of its centre in most of the frames it was seen
/// in (not predicted); clutter when that is none. `truth` as tracking_truth gives it.
std::size_t followed_class(const TrackHistory& history, const std::vector<std::vector<TruthCentre>>& truth);

/// Rows to train on from one rendered sequence: each track's features after 4, 8, 16, 32, ...
/// frames and at its end (a classifier must answer early in a track too), labelled with
/// followed_class.
void add_training_rows(const Sequence& s, const DetectorConfig& config, std::vector<TrackFeatures>& features,
                       std::vector<std::size_t>& labels);

/// The class of every confirmed track in every frame, from its samples up to that frame (what a
/// deployed detector knows then): result[frame][k] belongs to tracked[frame][k].
std::vector<std::vector<TrackClass>> classify_tracks(const std::vector<double>& time_s,
                                                     const std::vector<std::vector<TrackedObject>>& tracked,
                                                     const TrackClassifier& classifier);

/// eval's `classification` from a detections report's tracks with "class": per track, its class
/// at its last frame against followed_class: per_class precision and recall (null where
/// undefined), confusion[true][predicted] in tracks, and frames_to_settle (mean and median over
/// tracks of the frames from a track's first until its class last changed, 1 when it never
/// changed). Null when the tracks carry no class.
nlohmann::json classification_scores(const Sequence& s, const nlohmann::json& tracks);

}  // namespace ladarsim::detect
