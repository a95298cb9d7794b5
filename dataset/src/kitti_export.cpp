#include "ladarsim/dataset/kitti_export.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <regex>

#include "ladarsim/dataset/atomic_file.h"
#include "ladarsim/dataset/frame_io.h"
#include "ladarsim/dataset/frame_pcd.h"
#include "ladarsim/dataset/ground_truth_file.h"
#include "ladarsim/dataset/input_error.h"
#include "ladarsim/dataset/json_file.h"
#include "ladarsim/dataset/manifest.h"

namespace ladarsim {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// An angle in [-pi, pi).
double wrapped(double angle_rad) { return angle_rad - 2.0 * kPi * std::floor((angle_rad + kPi) / (2.0 * kPi)); }

/// KITTI's camera frame from the velodyne frame: x right = -y, y down = -z, z forward = x.
Eigen::Vector3d camera_from_velodyne(const Eigen::Vector3d& p) { return {-p.y(), -p.z(), p.x()}; }

const std::map<std::string, std::string>& type_of_class() {
    static const std::map<std::string, std::string> types{{"drone", "Drone"}, {"bird", "Bird"}, {"plane", "Plane"}};
    return types;
}

/// Little-endian whatever the host, as KITTI's readers (np.fromfile with '<f4') assume.
void append_float32_le(std::string& bytes, float value) {
    std::uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<char>((bits >> (8 * i)) & 0xFFu));
}

/// A velodyne .bin: x y z intensity per return, float32, intensity divided by `intensity_scale`.
std::string velodyne_bytes(const std::vector<Return>& returns, float intensity_scale) {
    std::string bytes;
    bytes.reserve(16 * returns.size());
    for (const Return& r : returns) {
        for (int axis = 0; axis < 3; ++axis) append_float32_le(bytes, r.position_sensor[axis]);
        append_float32_le(bytes, std::max(0.0f, r.intensity / intensity_scale));
    }
    return bytes;
}

void write_text(const std::filesystem::path& path, const std::string& text) {
    AtomicFile file(path);
    file.stream() << text;
    file.commit();
}

/// The frame index a frame file's name holds (NNNNNN.pcd), as ground truth names frames.
std::uint64_t frame_index_of(const std::filesystem::path& pcd, const std::filesystem::path& truth_file) {
    const std::string stem = pcd.stem().string();
    if (stem.empty() || stem.size() > 19 || !std::all_of(stem.begin(), stem.end(), [](char c) { return c >= '0' && c <= '9'; }))
        throw InputError(pcd.string(), "(name)",
                         "is not named NNNNNN.pcd, so its frame in " + truth_file.string() + " cannot be found");
    return std::stoull(stem);
}

/// Each frame file's ground truth; none for a recorded dataset (no ground_truth.json). Throws
/// InputError, before anything is written, for a frame ground truth lacks.
std::vector<std::optional<FrameGroundTruth>> ground_truth_of_frames(const std::filesystem::path& dataset_dir,
                                                                    const std::vector<std::filesystem::path>& pcds) {
    std::vector<std::optional<FrameGroundTruth>> of_frames(pcds.size());
    const auto file = dataset_dir / "ground_truth.json";
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) return of_frames;
    std::map<std::uint64_t, FrameGroundTruth> by_index;
    for (auto& f : read_ground_truth_json(file)) by_index[f.index] = std::move(f);
    for (std::size_t i = 0; i < pcds.size(); ++i) {
        const std::uint64_t index = frame_index_of(pcds[i], file);
        const auto it = by_index.find(index);
        if (it == by_index.end())
            throw InputError(file.string(), "frames", "has no frame " + std::to_string(index) + " for " + pcds[i].string());
        of_frames[i] = std::move(it->second);
    }
    return of_frames;
}

/// The label_2 lines of a frame: its objects of a labelled class with returns in it.
std::vector<std::string> label_lines(const std::vector<GroundTruthObject>& truth, const std::vector<Return>& returns) {
    std::map<std::uint32_t, std::uint32_t> returns_of_object;
    for (const Return& r : returns) ++returns_of_object[r.object_id];
    std::vector<std::string> lines;
    for (const GroundTruthObject& o : truth) {
        const auto type = kitti_type(o.object_class);
        if (type && returns_of_object[o.object_id] > 0) lines.push_back(kitti_label_line(*type, kitti_box(o.box_sensor)));
    }
    return lines;
}

float largest_intensity(const std::vector<std::filesystem::path>& pcds, const KittiExportProgress& progress) {
    float largest = 0.0f;
    for (std::size_t i = 0; i < pcds.size(); ++i) {
        for (const Return& r : read_frame_pcd(pcds[i])) largest = std::max(largest, r.intensity);
        if (progress.intensity_scanned) progress.intensity_scanned(static_cast<int>(i + 1), static_cast<int>(pcds.size()));
    }
    return largest;
}

nlohmann::json export_record(const std::filesystem::path& dataset_dir, const Manifest& manifest, float intensity_scale,
                             nlohmann::json frames) {
    return {{"software", software_json()},
            {"exported_from", dataset_dir.string()},
            {"dataset_id", manifest.id},
            {"format", "KITTI object detection (training/velodyne, label_2, calib); no image_2: no camera"},
            {"velodyne_frame", "ladarsim's sensor frame unrotated: x forward, y left, z up, metres, sensor at the origin"},
            {"camera_frame", "Tr_velo_to_cam: x right = -y, y down = -z, z forward = x; R0_rect and P0..P3 identity"},
            {"intensity", {{"kitti", "ladarsim intensity (primary photo-electrons, or the recording's unit) / scale, "
                                     "negative values written as 0"},
                           {"scale", intensity_scale}}},
            {"labels", "one per object of a labelled class with returns in the frame; box: the tightest box turned "
                       "about the vertical only that encloses ground truth's box_sensor; truncated 0, occluded 3 "
                       "(unknown), bbox -1 -1 -1 -1 (no image)"},
            {"class_map", type_of_class()},
            {"not_labelled", "every other class (the scene: building, terrain, tree, cloud, background)"},
            {"frames", std::move(frames)}};
}

}  // namespace

KittiBox kitti_box(const OrientedBox& box_sensor) {
    const Eigen::Matrix3d axes = box_sensor.orientation.normalized().toRotationMatrix();
    const Eigen::Vector3d nose = axes.col(0), left = axes.col(1);
    const double yaw = std::hypot(nose.x(), nose.y()) > 1e-9 ? std::atan2(nose.y(), nose.x())
                                                               : std::atan2(left.y(), left.x()) - kPi / 2;
    const Eigen::Vector3d along(std::cos(yaw), std::sin(yaw), 0.0), across(-std::sin(yaw), std::cos(yaw), 0.0),
        up(0.0, 0.0, 1.0);
    // Extent of the box along a direction: its three edges projected on it.
    const auto extent = [&](const Eigen::Vector3d& direction) {
        return (axes.transpose() * direction).cwiseAbs().dot(box_sensor.size);
    };
    KittiBox k;
    k.length_m = extent(along);
    k.width_m = extent(across);
    k.height_m = extent(up);
    k.bottom_centre_camera = camera_from_velodyne(box_sensor.centre - Eigen::Vector3d(0.0, 0.0, k.height_m / 2));
    // A nose along velodyne (cos yaw, sin yaw, 0) is camera (-sin yaw, 0, cos yaw), which KITTI's
    // roty(ry) makes of its +x when ry = -yaw - pi/2.
    k.rotation_y_rad = wrapped(-yaw - kPi / 2);
    k.alpha_rad = wrapped(k.rotation_y_rad - std::atan2(k.bottom_centre_camera.x(), k.bottom_centre_camera.z()));
    return k;
}

std::optional<std::string> kitti_type(const std::string& object_class) {
    const auto it = type_of_class().find(object_class);
    if (it == type_of_class().end()) return std::nullopt;
    return it->second;
}

std::string kitti_label_line(const std::string& type, const KittiBox& box) {
    char line[512];
    const Eigen::Vector3d& p = box.bottom_centre_camera;
    std::snprintf(line, sizeof line, "%s 0.00 3 %.6f -1.00 -1.00 -1.00 -1.00 %.6f %.6f %.6f %.6f %.6f %.6f %.6f",
                  type.c_str(), box.alpha_rad, box.height_m, box.width_m, box.length_m, p.x(), p.y(), p.z(),
                  box.rotation_y_rad);
    return line;
}

const std::string& kitti_calib_text() {
    static const std::string text = [] {
        const auto row = [](const std::string& key, std::initializer_list<double> values) {
            std::string line = key + ":";
            char number[32];
            for (const double v : values) {
                std::snprintf(number, sizeof number, " %.12e", v);
                line += number;
            }
            return line + "\n";
        };
        const std::initializer_list<double> identity_3x4 = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
        return row("P0", identity_3x4) + row("P1", identity_3x4) + row("P2", identity_3x4) + row("P3", identity_3x4) +
               row("R0_rect", {1, 0, 0, 0, 1, 0, 0, 0, 1}) +
               row("Tr_velo_to_cam", {0, -1, 0, 0, 0, 0, -1, 0, 1, 0, 0, 0}) + row("Tr_imu_to_velo", identity_3x4);
    }();
    return text;
}

const OutputLayout& kitti_layout() {
    static const OutputLayout layout{
        "export",
        [](const std::string& name) { return name == "training" || name == "ladarsim_export.json"; },
        [](const std::string& relative) {
            static const std::regex own(
                R"(training/(velodyne|label_2|calib)|training/velodyne/\d{6,}\.bin(\.tmp)?|training/(label_2|calib)/\d{6,}\.txt(\.tmp)?)");
            return std::regex_match(relative, own);
        }};
    return layout;
}

KittiExportSummary export_kitti(const std::filesystem::path& dataset_dir, const std::filesystem::path& out_dir,
                                const KittiExportProgress& progress) {
    std::error_code ec;
    if (!std::filesystem::is_directory(dataset_dir, ec))
        throw InputError(dataset_dir.string(), "DIR",
                         std::filesystem::exists(dataset_dir, ec) ? "is not a directory" : "no such directory");
    const std::filesystem::path source = std::filesystem::absolute(dataset_dir).lexically_normal();
    const Manifest manifest = read_manifest(source / "manifest.json");
    const auto pcds = frame_pcd_files(source);
    const auto truth = ground_truth_of_frames(source, pcds);

    KittiExportSummary summary;
    summary.out = checked_output_dir(out_dir, kitti_layout());
    const float largest = largest_intensity(pcds, progress);
    summary.intensity_scale = largest > 0.0f ? largest : 1.0f;

    const StagingDir staging_lock(summary.out);
    staging_lock.clear();
    const std::filesystem::path& staging = staging_lock.path();
    for (const char* d : {"velodyne", "label_2", "calib"}) std::filesystem::create_directories(staging / "training" / d);
    nlohmann::json frames = nlohmann::json::array();
    for (std::size_t i = 0; i < pcds.size(); ++i) {
        const std::vector<Return> returns = read_frame_pcd(pcds[i]);
        const std::string stem = frame_file_stem(i);
        write_text(staging / "training" / "velodyne" / (stem + ".bin"), velodyne_bytes(returns, summary.intensity_scale));
        nlohmann::json entry = {{"kitti", stem}, {"pcd", "frames/" + pcds[i].filename().string()}, {"returns", returns.size()}};
        std::vector<std::string> lines;
        if (truth[i]) {
            lines = label_lines(truth[i]->objects, returns);
            entry["frame_index"] = truth[i]->index;
        }
        std::string labels;
        for (const auto& line : lines) labels += line + "\n";
        write_text(staging / "training" / "label_2" / (stem + ".txt"), labels);
        entry["labels"] = lines.size();
        frames.push_back(std::move(entry));
        summary.labels += lines.size();
        write_text(staging / "training" / "calib" / (stem + ".txt"), kitti_calib_text());
        summary.returns += returns.size();
        if (progress.frame_written) progress.frame_written(static_cast<int>(i + 1), static_cast<int>(pcds.size()));
    }
    summary.frames = static_cast<int>(pcds.size());
    write_json(staging / "ladarsim_export.json", export_record(source, manifest, summary.intensity_scale, std::move(frames)));
    summary.kept = swap_in_output(staging, summary.out);
    return summary;
}

}  // namespace ladarsim
