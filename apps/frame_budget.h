#pragma once
// Whether a render's frames can fit where they go, checked before the first frame: a typing slip
// in --frames otherwise shows itself as a full disk hours later.
#include <filesystem>
#include <string>

namespace ladarsim::apps {

/// Throws InputError(file, field, ...) (the scenario's render.frames, or --frames) when `frames` cannot fit on the file system of `out_dir`
/// (or of its nearest existing parent): while rendering, each frame has four files in the staging
/// directory (point cloud, range image, ground truth, record), each taking an inode and at least
/// one block whatever it holds. A lower bound: passing it does not promise the frames fit.
void check_frames_fit_on_disk(int frames, const std::string& file, const std::string& field, const std::filesystem::path& out_dir);

}  // namespace ladarsim::apps
