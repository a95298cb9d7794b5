#pragma once
// Where every object really was, frame by frame: the reference detect/ is scored against.
//   {"frames": [{"index", "start_time_s", "end_time_s",
//                "sensor_pose": {"position_m", "orientation_wxyz"} (at the frame's start; optional),
//                "objects": [{"id", "class", "name", "time_s", "returns",
//                             "box_world":  {"centre_m": [x, y, z], "size_m": [x, y, z],
//                                            "orientation_wxyz": [w, x, y, z]},
//                             "box_sensor": {...}}]}]}
#include <cstdint>
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladarsim/dataset/frame.h"

namespace ladarsim {

/// One frame's ground truth without its returns, so a renderer can keep every frame's truth
/// until the end of a run and write it once.
struct FrameGroundTruth {
    std::uint64_t index = 0;
    double start_time_s = 0.0;
    double end_time_s = 0.0;
    std::vector<GroundTruthObject> objects;
    std::optional<Eigen::Isometry3d> sensor_pose;  ///< world_from_sensor at the frame's start
};

FrameGroundTruth ground_truth_of(const Frame& frame);

/// One object of a frame as ground_truth.json holds it: {"id", "class", "name", "time_s",
/// "returns", "folded_returns", "saturated_returns", "box_world", "box_sensor"}.
nlohmann::json ground_truth_object_json(const GroundTruthObject& object);

/// Atomic (see AtomicFile).
void write_ground_truth_json(const std::filesystem::path& path, const std::vector<FrameGroundTruth>& frames);

/// Throws InputError naming the file and the field path (e.g. "frames[3].objects[0].box_world.size_m")
/// of the first missing, mistyped, out-of-range or unknown field.
std::vector<FrameGroundTruth> read_ground_truth_json(const std::filesystem::path& path);

}  // namespace ladarsim
