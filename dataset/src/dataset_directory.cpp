#include "ladarsim/dataset/dataset_directory.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <regex>

#include "ladarsim/core/input_error.h"
#include "ladarsim/dataset/frame_io.h"

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

bool contains(const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

void write_owned_entries(const std::filesystem::path& dir, std::vector<std::string> names) {
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    std::string text = "# ladarsim wrote these entries of this directory: a new run replaces or deletes these and nothing else\n";
    for (const auto& n : names) text += n + "\n";
    // Under a temporary name of this process's own (AtomicFile's is shared): the shards of a
    // campaign, on one host or several, may list the same entries at the same moment.
    char host[256] = "";
    ::gethostname(host, sizeof host - 1);
    const std::filesystem::path list = dir / kOwnedList;
    const std::filesystem::path temporary = list.string() + "." + host + "." + std::to_string(::getpid()) + ".tmp";
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out << text;
        out.close();
        if (!out) {
            const std::string reason = std::strerror(errno);
            std::error_code ignored;
            std::filesystem::remove(temporary, ignored);
            throw std::runtime_error(list.string() + ": cannot write: " + reason);
        }
    }
    std::filesystem::rename(temporary, list);
}

/// The user's entries inside ladarsim's own directories of `out` (those on its owned list), as
/// relative paths, sorted; a directory of the user's is named, not entered.
std::vector<std::string> foreign_entries(const std::filesystem::path& out, const std::vector<std::string>& owned,
                                         const OutputLayout& layout) {
    std::vector<std::string> foreign;
    std::error_code ec;
    std::vector<std::string> own_dirs;
    for (const auto& name : owned)
        if (std::filesystem::is_directory(out / name, ec) && layout.is_own_entry(name)) own_dirs.push_back(name);
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
    return name == "frames" || name == "manifest.json" || name == "ground_truth.json" || name == "background.pcd" ||
           name == "poses.txt" || name == "waveforms";
}

std::optional<std::vector<std::string>> owned_entries(const std::filesystem::path& dir) {
    std::ifstream in(dir / kOwnedList);
    if (!in) return std::nullopt;
    std::vector<std::string> names;
    for (std::string line; std::getline(in, line);)
        if (!line.empty() && line[0] != '#') names.push_back(line);
    return names;
}

void check_replaceable(const std::filesystem::path& file, const std::string& field, bool force) {
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec))
        throw InputError(file.string(), field, "is a directory; give the name of a file inside it");
    const std::filesystem::path dir = file.parent_path().empty() ? "." : file.parent_path();
    if (!std::filesystem::is_directory(dir, ec))
        throw InputError(file.string(), field, "its directory " + dir.string() + " does not exist");
    if (force || !std::filesystem::exists(file, ec)) return;
    const auto owned = owned_entries(dir);
    if (owned && contains(*owned, file.filename().string())) return;
    throw InputError(file.string(), field, "exists and ladarsim did not write it; refusing to replace it (--force replaces it)");
}

void record_owned(const std::filesystem::path& file) {
    record_owned(file.parent_path().empty() ? "." : file.parent_path(), {file.filename().string()});
}

void record_owned(const std::filesystem::path& dir, const std::vector<std::string>& names) {
    auto owned = owned_entries(dir).value_or(std::vector<std::string>{});
    if (std::all_of(names.begin(), names.end(), [&](const std::string& n) { return contains(owned, n); })) return;
    owned.insert(owned.end(), names.begin(), names.end());
    write_owned_entries(dir, owned);
}

bool is_mount_point(const std::filesystem::path& dir) {
    struct stat self {}, parent {};
    if (::stat(dir.c_str(), &self) != 0 || ::stat(dir.parent_path().c_str(), &parent) != 0) return false;
    return self.st_dev != parent.st_dev;
}

const OutputLayout& dataset_layout() {
    static const OutputLayout layout{"dataset", is_dataset_entry, [](const std::string& relative) {
                                         const auto path = std::filesystem::path(relative);
                                         static const std::regex waveform_file(R"(\d{6,}\.h5(\.tmp)?)");
                                         if (path.parent_path() == "waveforms") return std::regex_match(path.filename().string(), waveform_file);
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
    const auto owned = owned_entries(out);
    if (!owned) {
        if (std::filesystem::is_empty(out, ec)) return out;
        throw InputError(out.string(), "--out",
                         "is a non-empty directory without the " + std::string(kOwnedList) + " list ladarsim writes in every " +
                             layout.what + "; refusing to replace it");
    }
    // A list naming only files written one by one into a directory of the user's (eval --json,
    // sensor from-ouster --out) or another kind of output (a campaign) makes it no such output.
    if (std::none_of(owned->begin(), owned->end(), layout.is_own_entry)) {
        const bool only_the_list = std::all_of(std::filesystem::directory_iterator(out), std::filesystem::directory_iterator(),
                                               [](const auto& e) { return e.path().filename() == kOwnedList; });
        if (!only_the_list)
            throw InputError(out.string(), "--out",
                             "holds no " + layout.what + " (ladarsim wrote only " + joined(*owned) + " there); refusing to write a " +
                                 layout.what + " into it");
    }
    std::vector<std::string> clashing;
    for (const auto& e : std::filesystem::directory_iterator(out)) {
        const std::string name = e.path().filename().string();
        if (layout.is_own_entry(name) && !contains(*owned, name)) clashing.push_back(entry_name(e));
    }
    std::sort(clashing.begin(), clashing.end());
    if (!clashing.empty())
        throw InputError(out.string(), "--out",
                         "holds " + joined(clashing) + ", which ladarsim did not write (not in " + kOwnedList + ") and a new " +
                             layout.what + " would replace; move them out first");
    if (const auto foreign = foreign_entries(out, *owned, layout); !foreign.empty()) {
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

StagingDir::StagingDir(const std::filesystem::path& out) : dir_(staging_dir(out)) {
    std::filesystem::create_directories(dir_);
    fd_ = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd_ < 0) throw std::runtime_error(dir_.string() + ": cannot open: " + std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
        ::close(fd_);
        throw InputError(out.string(), "--out",
                         "another ladarsim run is writing there (" + dir_.filename().string() +
                             " is locked); wait for it to finish or give another --out");
    }
}

StagingDir::~StagingDir() { ::close(fd_); }

void StagingDir::clear() const {
    for (const auto& e : std::filesystem::directory_iterator(dir_)) std::filesystem::remove_all(e.path());
}

std::vector<std::string> swap_in_output(const std::filesystem::path& staging, const std::filesystem::path& out) {
    std::vector<std::string> staged;
    for (const auto& e : std::filesystem::directory_iterator(staging))
        if (e.path().filename() != kOwnedList) staged.push_back(e.path().filename().string());
    if (!std::filesystem::exists(out)) {
        write_owned_entries(staging, staged);
        std::filesystem::rename(staging, out);
        return {};
    }
    const std::vector<std::string> owned = owned_entries(out).value_or(std::vector<std::string>{});
    for (const auto& name : staged)
        if (std::filesystem::exists(out / name) && !contains(owned, name))
            throw InputError(out.string(), "--out", "holds " + name + ", which ladarsim did not write; refusing to replace it");
    // Listed before they move in, so that an interrupted swap leaves every entry of ours listed.
    std::vector<std::string> listed = owned;
    listed.insert(listed.end(), staged.begin(), staged.end());
    write_owned_entries(out, listed);
    // Entry by entry, so that `out` itself (a mount's or link's target, the current directory)
    // stays, and so do the user's files in it. The replaced entries wait inside the staging
    // directory, which goes last.
    const std::filesystem::path old = staging / ".replaced";
    std::filesystem::create_directory(old);
    for (const auto& name : owned)
        if (std::filesystem::exists(std::filesystem::symlink_status(out / name))) std::filesystem::rename(out / name, old / name);
    for (const auto& name : staged) std::filesystem::rename(staging / name, out / name);
    write_owned_entries(out, staged);
    std::filesystem::remove_all(staging);
    std::vector<std::string> kept;
    for (const auto& e : std::filesystem::directory_iterator(out))
        if (e.path().filename() != kOwnedList && !contains(staged, e.path().filename().string())) kept.push_back(entry_name(e));
    std::sort(kept.begin(), kept.end());
    return kept;
}

std::vector<std::string> swap_in_dataset(const std::filesystem::path& staging, const std::filesystem::path& out) {
    return swap_in_output(staging, out);
}

std::string kept_files_note(const std::vector<std::string>& kept, const std::filesystem::path& out) {
    if (kept.empty()) return "";
    return "kept your files in " + out.string() + " (not written by ladarsim): " + joined(kept);
}

std::vector<std::string> write_recorded_dataset(const std::vector<Frame>& frames, const nlohmann::json& sensor,
                                                const std::filesystem::path& out_dir, const std::filesystem::path& source) {
    const std::filesystem::path out = checked_dataset_dir(out_dir);
    if (const auto owned = owned_entries(out); owned && std::find(owned->begin(), owned->end(), "ground_truth.json") != owned->end())
        throw InputError(out.string(), "--out",
                         "holds a rendered dataset, whose ground truth and initial map a recording would replace; import into "
                         "another directory");
    const StagingDir staging_lock(out);
    staging_lock.clear();
    const std::filesystem::path& staging = staging_lock.path();
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
