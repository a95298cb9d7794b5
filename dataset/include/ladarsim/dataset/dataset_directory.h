#pragma once
// A dataset directory and how it is written: every file is staged in `<out>.partial`, whose
// entries replace ladarsim's own entries of `<out>` only once complete, so an interrupted run
// leaves a previous dataset untouched, a finished one never mixes with stale frames, and the
// user's own files beside a dataset (notes, analyses) are kept.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladarsim/dataset/frame.h"
#include "ladarsim/dataset/manifest.h"

namespace ladarsim {

/// Whether a directory entry named `name` at the top of a dataset is ladarsim's: the dataset's own
/// files (frames/, manifest.json, ground_truth.json, background.pcd) and what ladarsim derives
/// from them beside them (detections-*.json, eval-*.json, preview.png), which would be stale
/// beside new frames. Everything else is the user's and is kept.
bool is_dataset_entry(const std::string& name);

/// How ladarsim tells its own entries from the user's in a directory it writes (a dataset, an
/// export), so that a new run replaces the first and keeps the second.
struct OutputLayout {
    std::string what;    ///< names the directory in messages: "dataset"
    std::string marker;  ///< the top-level file every run writes, marking the directory as ladarsim's
    /// Whether a top-level entry is ladarsim's (replaced by a new run).
    std::function<bool(const std::string& name)> is_own_entry;
    /// Whether an entry inside one of ladarsim's top-level directories, by its relative path
    /// ("frames/000001.pcd"), is ladarsim's: anything else there is the user's and would be lost.
    std::function<bool(const std::string& relative_path)> is_own_inside;
};

/// A dataset's layout: marker manifest.json, own entries is_dataset_entry's, frames/ holding
/// only frame files.
const OutputLayout& dataset_layout();

/// The output directory as an absolute path without a trailing separator (a symbolic link
/// resolved to its target), checked before anything is written: it may be absent, empty, or what
/// a previous run wrote (with the layout's marker; its own entries are replaced), never some
/// other directory a user would lose, one with a file of the user's inside ladarsim's own
/// directories, a link to nothing, or a mount point (the output is staged beside it, on its
/// parent's file system, and could not be moved in). Throws InputError naming it and "--out"
/// otherwise.
std::filesystem::path checked_output_dir(const std::filesystem::path& requested, const OutputLayout& layout);

/// checked_output_dir for a dataset.
std::filesystem::path checked_dataset_dir(const std::filesystem::path& requested);

/// Whether directory `dir` is on another file system than its parent (a mount point).
bool is_mount_point(const std::filesystem::path& dir);

/// Where the output for `out` is built: `<out>.partial`.
std::filesystem::path staging_dir(const std::filesystem::path& out);

/// Moves the finished staging directory's entries into `out` (created if absent), replacing
/// ladarsim's entries (the layout's) of a previous run there; `out` itself is never replaced.
/// Returns the names of the entries of `out` that were kept (the user's; a directory's name ends
/// in '/'), sorted.
std::vector<std::string> swap_in_output(const std::filesystem::path& staging, const std::filesystem::path& out,
                                        const OutputLayout& layout);

/// swap_in_output for a dataset.
std::vector<std::string> swap_in_dataset(const std::filesystem::path& staging, const std::filesystem::path& out);

/// "; kept your files in DIR: a, b/" for a summary line, or "" when `kept` is empty.
std::string kept_files_note(const std::vector<std::string>& kept, const std::filesystem::path& out);

/// Writes recorded frames (e.g. decoded Velodyne packets) as a dataset detect/ reads:
/// frames/NNNNNN.pcd and a manifest.json naming the source and holding `sensor` (the recording
/// sensor's parameters, as a render's manifest holds them); no ground truth, no initial map.
/// The rules for `out_dir` are checked_dataset_dir's; returns the user's entries kept there
/// (see swap_in_dataset).
std::vector<std::string> write_recorded_dataset(const std::vector<Frame>& frames, const nlohmann::json& sensor,
                            const std::filesystem::path& out_dir, const std::filesystem::path& source);

}  // namespace ladarsim
