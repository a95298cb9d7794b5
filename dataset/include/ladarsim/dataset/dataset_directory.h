#pragma once
// A dataset directory and how it is written: every file is staged in `<out>.partial`, whose
// entries replace ladarsim's own entries of `<out>` only once complete, so an interrupted run
// leaves a previous dataset untouched, a finished one never mixes with stale frames, and the
// user's own files beside a dataset (notes, analyses) are kept.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladarsim/dataset/frame.h"

namespace ladarsim {

/// Whether a directory entry named `name` at the top of a dataset is ladarsim's: the dataset's own
/// files (frames/, manifest.json, ground_truth.json, background.pcd) and what ladarsim derives
/// from them beside them (detections-*.json, eval-*.json, preview.png), which would be stale
/// beside new frames. Everything else is the user's and is kept.
bool is_dataset_entry(const std::string& name);

/// The output directory as an absolute path without a trailing separator (a symbolic link
/// resolved to its target), checked before anything is written: it may be absent, empty, or a
/// previous ladarsim dataset (whose own entries are replaced, see is_dataset_entry), never some
/// other directory a user would lose, a dataset with a file of the user's inside frames/, a link
/// to nothing, or a mount point (the dataset is staged beside it, on its parent's file system,
/// and could not be moved in). Throws InputError naming it and "--out" otherwise.
std::filesystem::path checked_dataset_dir(const std::filesystem::path& requested);

/// Whether directory `dir` is on another file system than its parent (a mount point).
bool is_mount_point(const std::filesystem::path& dir);

/// Where the dataset for `out` is built: `<out>.partial`.
std::filesystem::path staging_dir(const std::filesystem::path& out);

/// Moves the finished staging directory's entries into `out` (created if absent), replacing
/// ladarsim's entries of a previous dataset there; `out` itself is never replaced. Returns the
/// names of the entries of `out` that were kept (the user's; a directory's name ends in '/'),
/// sorted.
std::vector<std::string> swap_in_dataset(const std::filesystem::path& staging, const std::filesystem::path& out);

/// "; kept your files in DIR: a, b/" for a summary line, or "" when `kept` is empty.
std::string kept_files_note(const std::vector<std::string>& kept, const std::filesystem::path& out);

/// The "software" record of a manifest: this program's name and version.
nlohmann::json software_json();

/// Writes recorded frames (e.g. decoded Velodyne packets) as a dataset detect/ reads:
/// frames/NNNNNN.pcd and a manifest.json naming the source and holding `sensor` (the recording
/// sensor's parameters, as a render's manifest holds them); no ground truth, no initial map.
/// The rules for `out_dir` are checked_dataset_dir's; returns the user's entries kept there
/// (see swap_in_dataset).
std::vector<std::string> write_recorded_dataset(const std::vector<Frame>& frames, const nlohmann::json& sensor,
                            const std::filesystem::path& out_dir, const std::filesystem::path& source);

}  // namespace ladarsim
