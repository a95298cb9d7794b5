#include "ladarsim/dataset/dataset_directory.h"

#include <sys/stat.h>

#include <algorithm>
#include <regex>

#include "ladarsim/dataset/frame_io.h"
#include "ladarsim/core/input_error.h"

namespace ladarsim {

namespace {

std::string entry_name(const std::filesystem::directory_entry& e) {
    return e.path().filename().string() + (e.is_directory() ? "/" : "");
}

/// What ladarsim writes inside frames/: NNNNNN.pcd and .exr, a run's per-frame records, and the
/// temporaries of an interrupted write.
bool is_frame_file(const std::string& name) {
    static const std::regex frame_file(R"(\d{6,}\.(pcd|exr|log\.json|truth\.json)(\.tmp)?)");
    return std::regex_match(name, frame_file);
}

std::string joined(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

/// The user's entries inside ladarsim's own directories of `out`, as relative paths, sorted; a
/// directory of the user's is named, not entered.
std::vector<std::string> foreign_entries(const std::filesystem::path& out, const OutputLayout& layout) {
    std::vector<std::string> foreign;
    std::error_code ec;
    std::vector<std::string> own_dirs;
    for (const auto& e : std::filesystem::directory_iterator(out))
        if (e.is_directory(ec) && layout.is_own_entry(e.path().filename().string())) own_dirs.push_back(e.path().filename().string());
    while (!own_dirs.empty()) {
        const std::string dir = own_dirs.back();
        own_dirs.pop_back();
        for (const auto& e : std::filesystem::directory_iterator(out / dir)) {
            const std::string relative = dir + "/" + e.path().filename().string();
            if (!layout.is_own_inside(relative)) foreign.push_back(dir + "/" + entry_name(e));
            else if (e.is_directory(ec)) own_dirs.push_back(relative);
        }
    }
    std::sort(foreign.begin(), foreign.end());
    return foreign;
}

}  // namespace

bool is_dataset_entry(const std::string& name) {
    static const std::regex derived(R"((detections|eval)-.*\.json|preview\.png)");
    return name == "frames" || name == "manifest.json" || name == "ground_truth.json" || name == "background.pcd" ||
           std::regex_match(name, derived);
}

bool is_mount_point(const std::filesystem::path& dir) {
    struct stat self {}, parent {};
    if (::stat(dir.c_str(), &self) != 0 || ::stat(dir.parent_path().c_str(), &parent) != 0) return false;
    return self.st_dev != parent.st_dev;
}

const OutputLayout& dataset_layout() {
    static const OutputLayout layout{"dataset", "manifest.json", is_dataset_entry, [](const std::string& relative) {
                                         const auto path = std::filesystem::path(relative);
                                         return path.parent_path() == "frames" && is_frame_file(path.filename().string());
                                     }};
    return layout;
}

std::filesystem::path checked_output_dir(const std::filesystem::path& requested, const OutputLayout& layout) {
    std::filesystem::path out = std::filesystem::absolute(requested).lexically_normal();
    if (!out.has_filename()) out = out.parent_path();
    std::error_code ec;
    if (std::filesystem::is_symlink(out, ec)) {
        if (!std::filesystem::exists(out, ec))
            throw InputError(out.string(), "--out", "is a symbolic link to nothing (" +
                                                        std::filesystem::read_symlink(out, ec).string() + ")");
        // The link stays; the output goes where it points.
        out = std::filesystem::canonical(out, ec);
    }
    if (out == out.root_path()) throw InputError(out.string(), "--out", "is the root directory; give a directory inside it");
    if (!std::filesystem::exists(out, ec)) return out;
    if (!std::filesystem::is_directory(out, ec)) throw InputError(out.string(), "--out", "exists and is not a directory");
    if (is_mount_point(out))
        throw InputError(out.string(), "--out",
                         "is a mount point: the " + layout.what + " is staged beside it in " + out.filename().string() +
                             ".partial, on another file system, and could not be moved in; give a directory inside it, "
                             "e.g. --out " + (out / layout.what).string());
    if (!std::filesystem::is_empty(out, ec) && !std::filesystem::exists(out / layout.marker, ec))
        throw InputError(out.string(), "--out",
                         "is a non-empty directory without the " + layout.marker + " ladarsim writes in every " + layout.what +
                             "; refusing to replace it");
    if (const auto foreign = foreign_entries(out, layout); !foreign.empty()) {
        std::vector<std::string> dirs;
        for (const auto& f : foreign) dirs.push_back(f.substr(0, f.find('/') + 1));
        dirs.erase(std::unique(dirs.begin(), dirs.end()), dirs.end());
        throw InputError(out.string(), "--out",
                         "holds files ladarsim did not write inside " + joined(dirs) + ", which a new " + layout.what +
                             " replaces: " + joined(foreign) + "; move them out first");
    }
    return out;
}

std::filesystem::path checked_dataset_dir(const std::filesystem::path& requested) {
    return checked_output_dir(requested, dataset_layout());
}

std::filesystem::path staging_dir(const std::filesystem::path& out) { return out.string() + ".partial"; }

std::vector<std::string> swap_in_output(const std::filesystem::path& staging, const std::filesystem::path& out,
                                        const OutputLayout& layout) {
    const std::filesystem::path old = out.string() + ".old";
    std::filesystem::remove_all(old);
    if (!std::filesystem::exists(out)) {
        std::filesystem::rename(staging, out);
        return {};
    }
    // Entry by entry, so that `out` itself (a mount's or link's target, the current directory)
    // stays, and so do the user's files in it.
    std::vector<std::string> kept;
    std::filesystem::create_directory(old);
    for (const auto& e : std::filesystem::directory_iterator(out)) {
        if (layout.is_own_entry(e.path().filename().string())) std::filesystem::rename(e.path(), old / e.path().filename());
        else kept.push_back(entry_name(e));
    }
    for (const auto& e : std::filesystem::directory_iterator(staging)) std::filesystem::rename(e.path(), out / e.path().filename());
    std::filesystem::remove_all(staging);
    std::filesystem::remove_all(old);
    std::sort(kept.begin(), kept.end());
    return kept;
}

std::vector<std::string> swap_in_dataset(const std::filesystem::path& staging, const std::filesystem::path& out) {
    return swap_in_output(staging, out, dataset_layout());
}

std::string kept_files_note(const std::vector<std::string>& kept, const std::filesystem::path& out) {
    if (kept.empty()) return "";
    return "kept your files in " + out.string() + " (not written by ladarsim): " + joined(kept);
}

std::vector<std::string> write_recorded_dataset(const std::vector<Frame>& frames, const nlohmann::json& sensor,
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
    write_manifest(staging / "manifest.json", {sensor, log, {{"recorded_from", std::filesystem::absolute(source).string()}}});
    return swap_in_dataset(staging, out);
}

}  // namespace ladarsim
