#include "ladarsim/dataset/frame_io.h"

#include <algorithm>
#include <cstdio>
#include <system_error>

#include "ladarsim/core/input_error.h"

namespace ladarsim {

std::string frame_file_stem(std::uint64_t index) {
    char stem[24];
    std::snprintf(stem, sizeof stem, "%06llu", static_cast<unsigned long long>(index));
    return stem;
}

std::vector<std::filesystem::path> frame_pcd_files(const std::filesystem::path& dataset_dir) {
    std::error_code ec;
    const auto frames_dir = dataset_dir / "frames";
    if (!std::filesystem::is_directory(frames_dir, ec)) throw InputError(dataset_dir.string(), "frames", "no frames/ directory");
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(frames_dir))
        if (e.path().extension() == ".pcd") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    if (files.empty()) throw InputError(frames_dir.string(), "frames", "no .pcd frames");
    return files;
}

}  // namespace ladarsim
