#pragma once
// A rendered or recorded dataset as detect/ uses it, the runs of Algorithm 1 over it, and their
// scores against the ground truth.
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladarsim/dataset/ground_truth_file.h"
#include "ladarsim/detect/multi_target.h"
#include "ladarsim/detect/track_classifier.h"
#include "ladarsim/detect/tracker.h"
#include "ladarsim/detect/tracking_metrics.h"

namespace ladarsim::detect {

struct Sequence {
    std::filesystem::path directory;  ///< where load_sequence read it
    std::string dataset_id;           ///< Manifest::id: which dataset these frames are
    SensorGeometry sensor;   ///< from manifest.json
    std::vector<std::uint64_t> frame_index;
    std::vector<double> time_s;
    std::vector<Points> frames;
    std::vector<std::vector<float>> intensity;  ///< per frame, one per point of frames
    Points background;  ///< background.pcd; empty when the dataset has none
    /// Per frame, the unit direction of the gimbal's pointing from manifest.json (the radar cue),
    /// when the dataset has one.
    std::vector<std::optional<Eigen::Vector3d>> boresight;
    std::vector<FrameGroundTruth> truth;  ///< empty when there is no ground_truth.json
};

/// Reads DIR/manifest.json, DIR/frames/*.pcd (in name order), and DIR/background.pcd and
/// DIR/ground_truth.json when present. Throws InputError for a missing directory, no frames, a
/// manifest that does not say which sensor took the frames (read_manifest), or a malformed file.
Sequence load_sequence(const std::filesystem::path& dir);

/// The id of the first drone in the ground truth (the target to score), if any.
std::optional<std::uint32_t> default_target(const Sequence& s);

/// Checks that `target` is an object of the ground truth with a box in every frame, as scoring
/// needs. Throws InputError naming `truth_file` and "--target" and saying, in the user's terms,
/// which objects there are or in which frame the target is missing.
void check_target(const Sequence& s, std::uint32_t target, const std::filesystem::path& truth_file);

/// The ground-truth box of `target` in frame i, as the axis-aligned box enclosing it in the
/// sensor frame (the detector's boxes are axis-aligned there).
std::optional<OrientedBox> truth_box(const Sequence& s, std::size_t i, std::uint32_t target);

/// Algorithm 1 over every frame, as a deployed detector would run it.
std::vector<Detection> detect_sequence(const Sequence& s, const DetectorConfig& config);

/// MultiTargetTracker over every frame: the confirmed tracks of each.
std::vector<std::vector<TrackedObject>> track_sequence(const Sequence& s, const DetectorConfig& config);

/// The objects a tracker of every target should follow, per frame: drones, birds and aircraft
/// with at least one return in the frame (the static world and clouds are not targets), at the
/// centre of truth_box.
std::vector<std::vector<TruthCentre>> tracking_truth(const Sequence& s);

/// Which of a detection's boxes is scored (Detection::box, around its points, or sensor_box), and
/// whether by the overlap of volumes or of footprints seen from above (bird's-eye view).
enum class ScoredBox { points, sensor_aware };
enum class Overlap { volume, bev };
/// The IoU of a detection's box with the truth, 0 when it has none.
double overlap(const Detection& d, ScoredBox box, Overlap kind, const OrientedBox& truth);
/// The four scored kinds by name: "points_3d", "points_bev", "sensor_3d", "sensor_bev".
const std::vector<std::tuple<std::string, ScoredBox, Overlap>>& scored_kinds();

/// VOT's supervised protocol for EAO: run, and after a failure (IoU 0) skip 5 frames and
/// re-initialise on the ground truth. Per frame: IoU and whether the tracker was (re-)initialised.
/// A predicted box scores only after a detection has confirmed the track since the last
/// (re-)initialisation: replaying the ground truth it was handed is not tracking.
struct SupervisedRun {
    std::vector<double> iou;
    std::vector<bool> initialised;
    int failures = 0;
};
SupervisedRun supervised_run(const Sequence& s, const DetectorConfig& config, std::uint32_t target,
                             ScoredBox box = ScoredBox::points, Overlap kind = Overlap::volume);

/// A supervised run for each scored box and overlap: "points_3d", "points_bev", "sensor_3d",
/// "sensor_bev" (a failure, and so EAO, depends on which overlap is 0).
using SupervisedRuns = std::map<std::string, SupervisedRun>;
SupervisedRuns supervised_runs(const Sequence& s, const DetectorConfig& config, std::uint32_t target);

/// What a detections file records of the dataset it was computed on: its directory and manifest id.
nlohmann::json dataset_record(const Sequence& s);
/// Throws InputError(detections_file, "dataset", ...) naming both datasets when `detections` (a
/// detections file's JSON) were computed on another dataset than `s` (read from `dir`), or do not
/// say which.
void check_same_dataset(const nlohmann::json& detections, const std::string& detections_file, const Sequence& s);

/// A detection as detections files hold it (scoring.h reads it back): {"frame", "time_s", "found",
/// "predicted", "centre_m", "size_m", "sensor_box", "points", "radius_m"}.
nlohmann::json to_json(const Detection& d);

/// The settings a detection run records ("config" of its report): radius_m, lambda, bias_m,
/// resolution_m, range_tolerance_m, min_neighbours, max_diagonal_m, max_speed_mps, min_box_m,
/// max_object_diagonal_m, range_coherence_m, coherent_fraction, target_size_m.
/// `config` as a detection report records it, its lambda resolved for `sensor` (default_lambda).
nlohmann::json to_json(const DetectorConfig& config, const SensorGeometry& sensor);

/// A configuration from "method" (rbnn, vrbnn or kalman; default vrbnn) and any of the keys
/// to_json writes; the others keep DetectorConfig's defaults. Throws InputError(file, key,
/// problem) for an unknown key or a value of the wrong type or range.
DetectorConfig read_detector_config(const nlohmann::json& options, const std::string& file);

/// Algorithm 1 over a dataset as `ladarsim detect` reports it: {"method", "config", "dataset",
/// "detections" (to_json's, per frame), "tracks" (track_sequence's, per frame: {"frame", "objects":
/// [{track, centre_m, size_m, sensor_box, points, predicted, score}]})} and, when the ground truth
/// holds `target` (default: default_target), "target". Scores come from scoring.h: of the boxes
/// (evaluate_report), or with the tracker in the loop (benchmark_report).
/// With a classifier, each track object also has "class" and "class_confidence": its class from
/// what the track has shown up to that frame (classify_tracks).
nlohmann::json detection_report(const Sequence& s, const DetectorConfig& config,
                                std::optional<std::uint32_t> target = std::nullopt, const TrackClassifier* classifier = nullptr);

}  // namespace ladarsim::detect
