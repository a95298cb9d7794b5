#include "frame_budget.h"

#include <sys/statvfs.h>

#include <cstdint>
#include <string>

#include "ladarsim/core/input_error.h"

namespace ladarsim::apps {

namespace {

constexpr std::uint64_t kFilesPerFrame = 4;

std::string gigabytes(std::uint64_t bytes) {
    return std::to_string(bytes / 1'000'000'000) + "." + std::to_string(bytes / 100'000'000 % 10) + " GB";
}

}  // namespace

void check_frames_fit_on_disk(int frames, const std::string& file, const std::string& field, const std::filesystem::path& out_dir) {
    std::filesystem::path existing = std::filesystem::absolute(out_dir);
    std::error_code ec;
    while (!std::filesystem::exists(existing, ec) && existing.has_relative_path()) existing = existing.parent_path();
    struct statvfs fs {};
    if (::statvfs(existing.c_str(), &fs) != 0) return;  // nothing known: the writes will say
    const std::uint64_t files = kFilesPerFrame * static_cast<std::uint64_t>(frames);
    const std::uint64_t bytes = files * fs.f_frsize;
    const std::uint64_t free_bytes = static_cast<std::uint64_t>(fs.f_bavail) * fs.f_frsize;
    const std::string where = "; the file system of " + existing.string() + " has ";
    // A file system without a fixed number of inodes (btrfs) reports none at all.
    if (fs.f_files > 0 && files > fs.f_favail)
        throw InputError(file, field,
                         std::to_string(frames) + " frames are too many for the disk: rendering them takes " + std::to_string(files) + " files (" +
                             std::to_string(kFilesPerFrame) + " a frame)" + where + std::to_string(fs.f_favail) +
                             " free (df -i); render fewer frames or into another --out");
    if (bytes > free_bytes)
        throw InputError(file, field,
                         std::to_string(frames) + " frames are too many for the disk: rendering them takes at least " + gigabytes(bytes) + where +
                             gigabytes(free_bytes) + " free; render fewer frames or into another --out");
}

}  // namespace ladarsim::apps
