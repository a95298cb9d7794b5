#include "ladarsim/dataset/dataset_directory.h"

#include "ladarsim/dataset/frame_io.h"
#include "ladarsim/dataset/input_error.h"

namespace ladarsim {

std::filesystem::path checked_dataset_dir(const std::filesystem::path& requested) {
    std::filesystem::path out = std::filesystem::absolute(requested).lexically_normal();
    if (!out.has_filename()) out = out.parent_path();
    std::error_code ec;
    if (!std::filesystem::exists(out, ec)) return out;
    if (!std::filesystem::is_directory(out, ec)) throw InputError(out.string(), "--out", "exists and is not a directory");
    if (!std::filesystem::is_empty(out, ec) && !std::filesystem::exists(out / "manifest.json", ec))
        throw InputError(out.string(), "--out",
                         "is a non-empty directory without a ladarsim manifest.json; refusing to replace it");
    return out;
}

std::filesystem::path staging_dir(const std::filesystem::path& out) { return out.string() + ".partial"; }

void swap_in_dataset(const std::filesystem::path& staging, const std::filesystem::path& out) {
    const std::filesystem::path old = out.string() + ".old";
    std::filesystem::remove_all(old);
    if (std::filesystem::exists(out)) std::filesystem::rename(out, old);
    std::filesystem::rename(staging, out);
    std::filesystem::remove_all(old);
}

nlohmann::json software_json() { return {{"name", "ladarsim"}, {"version", LADARSIM_VERSION}}; }

void write_recorded_dataset(const std::vector<Frame>& frames, const nlohmann::json& sensor,
                            const std::filesystem::path& out_dir, const std::filesystem::path& source) {
    const std::filesystem::path out = checked_dataset_dir(out_dir);
    const std::filesystem::path staging = staging_dir(out);
    std::filesystem::remove_all(staging);
    std::filesystem::create_directories(staging / "frames");
    nlohmann::json log = nlohmann::json::array();
    for (const Frame& f : frames) {
        write_frame_pcd(staging / "frames" / (frame_file_stem(f.index) + ".pcd"), f);
        log.push_back({{"index", f.index}, {"start_time_s", f.start_time_s}, {"end_time_s", f.end_time_s},
                       {"returns", f.returns.size()}});
    }
    write_json(staging / "manifest.json", {{"software", software_json()},
                                           {"recorded_from", std::filesystem::absolute(source).string()},
                                           {"sensor", sensor},
                                           {"frames", log}});
    swap_in_dataset(staging, out);
}

}  // namespace ladarsim
