#pragma once
// Scores against the ground truth: of the boxes a detections file holds (`ladarsim eval`, any
// detector's file), and of a named detector run with the tracker in the loop (`ladarsim
// benchmark`: VOT's supervised EAO, which no file can carry honestly).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladarsim/detect/sequence.h"

namespace ladarsim::detect {

/// A detections file read against the dataset it scores, its frames in the dataset's order.
struct DetectionsFile {
    std::string method;  ///< "" when the file does not say
    std::uint32_t target = 0;
    std::vector<Detection> detections;  ///< one per frame of the dataset
    /// The tracks of every target, one list per frame of the dataset, when the file has "tracks".
    std::optional<std::vector<std::vector<TrackCentre>>> tracks;
    bool has_supervised_block = false;  ///< checked, never scored
};

/// Reads a detections file: {"dataset" (dataset_record's, required), "method", "config",
/// "target" (default: default_target), "detections": [{"frame", "found", "centre_m", "size_m"
/// (required when found), "sensor_box" (default: the same box), "predicted", "time_s", "points",
/// "radius_m"}], "tracks": [{"frame", "objects": [{"track", "centre_m", "size_m", "sensor_box",
/// "score", "points", "predicted"}]}], "supervised"}. Entries are matched to the dataset's frames
/// by "frame", in any order; each frame must appear once. A "supervised" block (older `detect`
/// reports) must be well formed (overlaps in [0, 1], one per frame) and is otherwise ignored.
/// Throws InputError naming `file` and the field: unknown keys, wrong types, sizes below 0,
/// frames the dataset lacks, missing or repeated frames, another dataset's file.
DetectionsFile read_detections_file(const Sequence& s, const nlohmann::json& report, const std::string& file);

/// What the boxes of a detections file score (`ladarsim eval`): "measures" (which it supports:
/// "average_overlap", "l2", and with tracks "mot", "ap"), "method", "target", "frames", mean L2
/// (frames with a box), mean IoU and bird's-eye IoU of the sensor-aware box (all frames, no
/// resets) and under "point_box" of the box around the points, "frames_lost", one-pass success
/// and precision, "per_frame"; with tracks, CLEAR MOT (2 m gate) and centre-distance AP against
/// tracking_truth ("mota", "motp_m", "id_switches", "ap_centre", "ap_centre_3d", "tracking").
nlohmann::json evaluate_report(const Sequence& s, const nlohmann::json& report, const std::string& file);

/// A named detector run and scored as it runs (`ladarsim benchmark`): evaluate_report of the
/// report detection_report writes, plus VOT's supervised protocol (supervised_runs) over the
/// interval of sequence lengths vot_length_interval gives: "eao", "eao_bev", "eao_interval",
/// "failures" and the same under "point_box"; per frame "supervised_iou" and "initialised";
/// "eao" among "measures". Needs ground truth holding `target` (default: default_target).
nlohmann::json benchmark_report(const Sequence& s, const DetectorConfig& config, std::optional<std::uint32_t> target = std::nullopt);

}  // namespace ladarsim::detect
