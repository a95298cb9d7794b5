#pragma once
// A dataset directory and how it is written: every file is staged in `<out>.partial`, whose
// entries replace ladarsim's own entries of `<out>` only once complete, so an interrupted run
// leaves a previous dataset untouched, a finished one never mixes with stale frames, and the
// user's own files beside a dataset (notes, analyses) are kept.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladarsim/dataset/frame.h"
#include "ladarsim/dataset/manifest.h"

namespace ladarsim {

/// Whether a directory entry named `name` at the top of a dataset is one a render writes there:
/// frames/, manifest.json, ground_truth.json, background.pcd, waveforms/ (render.waveforms).
bool is_dataset_entry(const std::string& name);

/// The file in every directory ladarsim writes (a dataset, an export) listing the entries at its
/// top that ladarsim wrote there, one a line. Only what it lists is ever replaced or deleted; a
/// directory without it is not ladarsim's. Files derived later (detect's detections, eval's
/// scores and plots written into a dataset) are added to it.
inline constexpr const char* kOwnedList = ".ladarsim-owned";

/// The entries `dir`'s owned list names (without a trailing '/'), or nullopt when it has none.
std::optional<std::vector<std::string>> owned_entries(const std::filesystem::path& dir);

/// Before writing a file the user named (`field` names the option): refuses with InputError when
/// it is a directory, or when it exists and ladarsim did not write it (its name is not on its
/// directory's owned list), unless `force`.
void check_replaceable(const std::filesystem::path& file, const std::string& field, bool force);

/// After writing `file`: adds it to its directory's owned list, so that a later run may replace
/// it (and, in a dataset, a new render deletes it as stale). In a directory of the user's the list
/// is made, naming only that file: such a directory is still no output of checked_output_dir's.
void record_owned(const std::filesystem::path& file);

/// The same for entries of `dir` a run is about to write (a campaign's): listed first, so that a
/// run stopped half-way leaves every entry of its own listed.
void record_owned(const std::filesystem::path& dir, const std::vector<std::string>& names);

/// How ladarsim writes a directory of its own (a dataset, an export), so that a new run replaces
/// what the previous one wrote (its owned list) and keeps the user's files.
struct OutputLayout {
    std::string what;  ///< names the directory in messages: "dataset"
    /// Whether a top-level entry is one this kind of run writes: a file of the user's so named
    /// would be replaced, and is refused.
    std::function<bool(const std::string& name)> is_own_entry;
    /// Whether an entry inside one of ladarsim's top-level directories, by its relative path
    /// ("frames/000001.pcd"), is ladarsim's: anything else there is the user's and would be lost.
    std::function<bool(const std::string& relative_path)> is_own_inside;
};

/// A dataset's layout: own entries is_dataset_entry's, frames/ holding only frame files,
/// waveforms/ only NNNNNN.h5.
const OutputLayout& dataset_layout();

/// The output directory as an absolute path without a trailing separator (a symbolic link
/// resolved to its target), checked before anything is written: it may be absent, empty, or what
/// a previous run wrote (with an owned list naming one of the layout's entries; the entries it
/// lists are replaced), never some other directory a user would lose, one where a file of the
/// user's has a name the run writes or sits inside ladarsim's own directories, a link to nothing,
/// or a mount point (the output is staged beside it, on its parent's file system, and could not be
/// moved in). Throws InputError naming it and "--out" otherwise.
std::filesystem::path checked_output_dir(const std::filesystem::path& requested, const OutputLayout& layout);

/// checked_output_dir for a dataset.
std::filesystem::path checked_dataset_dir(const std::filesystem::path& requested);

/// Whether directory `dir` is on another file system than its parent (a mount point).
bool is_mount_point(const std::filesystem::path& dir);

/// Where the output for `out` is built: `<out>.partial`.
std::filesystem::path staging_dir(const std::filesystem::path& out);

/// The staging directory of `out`, created if absent and locked (flock) while this lives: a second
/// run writing the same output is refused in one line instead of deleting the first one's files
/// under it. What an earlier run left there stays until clear().
class StagingDir {
public:
    /// Throws InputError naming `out` and "--out" when another run holds the lock.
    explicit StagingDir(const std::filesystem::path& out);
    ~StagingDir();
    StagingDir(const StagingDir&) = delete;
    StagingDir& operator=(const StagingDir&) = delete;

    const std::filesystem::path& path() const { return dir_; }
    /// Deletes what an earlier run left inside: a fresh start.
    void clear() const;

private:
    std::filesystem::path dir_;
    int fd_ = -1;
};

/// Moves the finished staging directory's entries into `out` (created if absent), replacing and
/// deleting the entries a previous run there listed in its owned list, and lists the new ones;
/// `out` itself is never replaced, nor an entry of the user's. Returns the names of the entries of
/// `out` that were kept (the user's; a directory's name ends in '/'), sorted.
std::vector<std::string> swap_in_output(const std::filesystem::path& staging, const std::filesystem::path& out);

/// swap_in_output for a dataset.
std::vector<std::string> swap_in_dataset(const std::filesystem::path& staging, const std::filesystem::path& out);

/// "; kept your files in DIR: a, b/" for a summary line, or "" when `kept` is empty.
std::string kept_files_note(const std::vector<std::string>& kept, const std::filesystem::path& out);

/// Writes recorded frames (e.g. decoded Velodyne packets) as a dataset detect/ reads:
/// frames/NNNNNN.pcd and a manifest.json naming the source and holding `sensor` (the recording
/// sensor's parameters, as a render's manifest holds them); no ground truth, no initial map.
/// The rules for `out_dir` are checked_dataset_dir's, and a rendered dataset there (with ground
/// truth and an initial map a recording cannot give back) is refused; returns the user's entries
/// kept there (see swap_in_dataset).
std::vector<std::string> write_recorded_dataset(const std::vector<Frame>& frames, const nlohmann::json& sensor,
                            const std::filesystem::path& out_dir, const std::filesystem::path& source);

}  // namespace ladarsim
