#pragma once
// A dataset directory and how it is written: every file is staged in `<out>.partial`, which
// replaces `<out>` only once complete, so an interrupted run leaves a previous dataset untouched
// and a finished one never mixes with stale frames.
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladarsim/dataset/frame.h"

namespace ladarsim {

/// The output directory as an absolute path without a trailing separator, checked before
/// anything is written: it may be absent, empty, or a previous ladarsim dataset (which is
/// replaced), never some other directory a user would lose. Throws InputError naming it and
/// "--out" otherwise.
std::filesystem::path checked_dataset_dir(const std::filesystem::path& requested);

/// Where the dataset for `out` is built: `<out>.partial`.
std::filesystem::path staging_dir(const std::filesystem::path& out);

/// Moves the finished staging directory to `out`, replacing a previous dataset there.
void swap_in_dataset(const std::filesystem::path& staging, const std::filesystem::path& out);

/// The "software" record of a manifest: this program's name and version.
nlohmann::json software_json();

/// Writes recorded frames (e.g. decoded Velodyne packets) as a dataset detect/ reads:
/// frames/NNNNNN.pcd and a manifest.json naming the source and holding `sensor` (the recording
/// sensor's parameters, as a render's manifest holds them); no ground truth, no initial map.
/// The rules for `out_dir` are checked_dataset_dir's.
void write_recorded_dataset(const std::vector<Frame>& frames, const nlohmann::json& sensor,
                            const std::filesystem::path& out_dir, const std::filesystem::path& source);

}  // namespace ladarsim
