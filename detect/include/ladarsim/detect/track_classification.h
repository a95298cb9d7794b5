#pragma once
// The tracks of a sequence as a classifier sees them: each track's history, what it follows in
// the ground truth, training rows from rendered sequences, and the class of each track in each
// frame from what it has shown so far.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "ladarsim/detect/multi_target.h"
#include "ladarsim/detect/track_classifier.h"
#include "ladarsim/detect/track_features.h"

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

/// A drone, bird or aircraft with returns in one frame, as a track may follow it: its class and
/// its box (truth_box: axis-aligned in the sensor frame).
struct FollowableObject {
    std::string object_class;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    Eigen::Vector3d size = Eigen::Vector3d::Zero();
};

/// The objects a track may follow in each frame of `s` (those of tracking_truth, with their boxes).
std::vector<std::vector<FollowableObject>> followable_truth(const Sequence& s);

/// What a track follows: in each frame it was seen in (not predicted), the nearest object whose
/// centre is within kFollowGate_m of the track's or whose box holds the track's centre (a track on
/// one wing of an aircraft follows the aircraft, metres from its centre); the class (index into
/// track_class_names()) followed in most of those frames, clutter when that is none.
std::size_t followed_class(const TrackHistory& history, const std::vector<std::vector<FollowableObject>>& truth);

/// The fewest frames with a cluster a track has shown before it is given a class: every feature
/// is defined by then (speed spread, acceleration, turn and the height's spread about its trend
/// need 3, the return count's periodogram kMinFlickerFrames; a predicted frame measures nothing).
/// A younger track's features are mostly zeros, which tell how young it is, not what it follows:
/// trained on, they taught that a short track is whatever class the campaign's short tracks mostly
/// are.
inline constexpr std::size_t kMinClassFrames = kMinFlickerFrames;

/// Rows to train on from one rendered sequence: each track's features after 4, 8, 16, 32, 64 frames
/// (a classifier must answer early in a track too), every 32 frames after that, and at its end,
/// labelled with followed_class; those of fewer than kMinClassFrames frames with a cluster left out.
void add_training_rows(const Sequence& s, const DetectorConfig& config, std::vector<TrackFeatures>& features,
                       std::vector<std::size_t>& labels);

/// The class of every confirmed track in every frame, from its samples up to that frame (what a
/// deployed detector knows then), none until it has kMinClassFrames frames with a cluster:
/// result[frame][k] belongs to tracked[frame][k].
std::vector<std::vector<std::optional<TrackClass>>> classify_tracks(const std::vector<double>& time_s,
                                                     const std::vector<std::vector<TrackedObject>>& tracked,
                                                     const TrackClassifier& classifier);

/// eval's `classification` from a detections report's tracks with "class": per track, its class
/// at its last frame against followed_class: per_class precision and recall (null where
/// undefined), confusion[true][predicted] in tracks, and frames_to_settle (mean and median over
/// tracks of the frames from a track's first class until its class last changed, 1 when it never
/// changed). A track whose class is null to its end (too short for one) is in none of those but in
/// unclassified[true] (tracks): a recall is of the classified tracks, and these say how many were not.
/// Null when the tracks carry no class key.
nlohmann::json classification_scores(const Sequence& s, const nlohmann::json& tracks);

}  // namespace ladarsim::detect
