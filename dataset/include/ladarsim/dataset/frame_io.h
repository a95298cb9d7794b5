#pragma once
// A rendered frame on disk: frames/NNNNNN.pcd (the point cloud), frames/NNNNNN.exr (the range
// image), plus ground_truth.json and manifest.json for the whole run. Every file is written
// atomically: it appears complete under its final name or not at all.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "ladarsim/dataset/exr_file.h"
#include "ladarsim/dataset/frame_pcd.h"
#include "ladarsim/dataset/ground_truth_file.h"
#include "ladarsim/core/json_file.h"

namespace ladarsim {

/// The file name of a frame without extension: six digits, zero-padded ("000042"), so that
/// names sort in frame order; larger indices simply use more digits.
std::string frame_file_stem(std::uint64_t index);

/// A dataset's point clouds, DIR/frames/*.pcd, in name order (the frames' order), rendered or
/// recorded. Throws InputError naming DIR for a missing frames/ directory, or frames/ when it
/// holds no .pcd file.
std::vector<std::filesystem::path> frame_pcd_files(const std::filesystem::path& dataset_dir);

}  // namespace ladarsim
