#include "ladarsim/dataset/kitti_export.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <regex>

#include "ladarsim/core/atomic_file.h"
#include "ladarsim/dataset/frame_io.h"
#include "ladarsim/dataset/frame_pcd.h"
#include "ladarsim/dataset/ground_truth_file.h"
#include "ladarsim/dataset/intensity_scale.h"
#include "ladarsim/core/input_error.h"
#include "ladarsim/core/json_file.h"
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

/// One label of a frame: the line label_2 holds, and what ladarsim_export.json records of it.
struct Label {
    std::string line;
    nlohmann::json record;  ///< {"id", "type", "returns", "exact_label": the line with ground truth's box}
};

/// The labels of a frame: its objects of a labelled class with returns in it.
std::vector<Label> frame_labels(const std::vector<GroundTruthObject>& truth, const std::vector<Return>& returns,
                                const KittiExportOptions& options) {
    std::map<std::uint32_t, std::vector<Eigen::Vector3d>> returns_of_object;
    for (const Return& r : returns) returns_of_object[r.object_id].push_back(r.position_sensor.cast<double>());
    std::vector<Label> labels;
    for (const GroundTruthObject& o : truth) {
        const auto type = kitti_type(o.object_class);
        const auto& own = returns_of_object[o.object_id];
        if (!type || own.empty()) continue;
        const std::string exact = kitti_label_line(*type, kitti_box(o.box_sensor));
        labels.push_back({options.exact_boxes ? exact : kitti_label_line(*type, kitti_label_box(o.box_sensor, own)),
                          {{"id", o.object_id}, {"type", *type}, {"returns", own.size()}, {"exact_label", exact}}});
    }
    return labels;
}

/// ladarsim_export.json: `origin` (where the frames came from) and what the export holds.
nlohmann::json export_record(nlohmann::json origin, float intensity_scale, const KittiExportOptions& options,
                             nlohmann::json frames) {
    nlohmann::json record = {{"software", software_json()}};
    record.update(origin);
    record.update(nlohmann::json{
        {"format", "KITTI object detection (training/velodyne, label_2, calib); no image_2: no camera"},
        {"velodyne_frame", "ladarsim's sensor frame unrotated: x forward, y left, z up, metres, sensor at the origin"},
        {"camera_frame", "Tr_velo_to_cam: x right = -y, y down = -z, z forward = x; R0_rect and P0..P3 identity"},
        {"intensity", {{"kitti", "ladarsim intensity (primary photo-electrons, or the recording's unit) / scale, "
                                 "negative values written as 0"},
                       {"scale", intensity_scale}}},
        {"labels", "one per object of a labelled class with returns in the frame, in ground truth's order (frames[].labels: "
                   "id, type, returns, exact_label); exact box: the tightest box turned about the vertical only "
                   "that encloses ground truth's box_sensor; label box: see label_boxes; truncated 0, occluded 3 "
                   "(unknown), bbox -1 -1 -1 -1 (no image)"},
        {"label_boxes", options.exact_boxes ? "exact" : "holding the returns"},
        {"label_boxes_are", options.exact_boxes
                                ? "the exact boxes (--exact-boxes)"
                                : "the exact box grown about its heading to the tightest box holding it and every return of "
                                  "the object label_margin_m inside its faces (a return lies on its beam's axis, up to half "
                                  "a footprint beside the object)"},
        {"label_margin_m", kKittiLabelMargin_m},
        {"class_map", type_of_class()},
        {"not_labelled", "every other class (the scene: building, terrain, tree, cloud, background)"},
        {"frames", std::move(frames)}});
    return record;
}

/// A source dataset read for export: its frames and their ground truth, checked before anything
/// is written.
struct SourceFrames {
    std::filesystem::path dir;  ///< absolute
    Manifest manifest;
    std::vector<std::filesystem::path> pcds;
    std::vector<std::optional<FrameGroundTruth>> truth;
};

SourceFrames read_source(const std::filesystem::path& dataset_dir) {
    std::error_code ec;
    if (!std::filesystem::is_directory(dataset_dir, ec))
        throw InputError(dataset_dir.string(), "DIR",
                         std::filesystem::exists(dataset_dir, ec) ? "is not a directory" : "no such directory");
    SourceFrames source;
    source.dir = std::filesystem::absolute(dataset_dir).lexically_normal();
    source.manifest = read_manifest(source.dir / "manifest.json");
    source.pcds = frame_pcd_files(source.dir);
    source.truth = ground_truth_of_frames(source.dir, source.pcds);
    return source;
}

/// Writes `sources` into `out_dir` as one export, frames numbered on from 000000 in the order
/// given; `origin` says in ladarsim_export.json where they came from, `split_of_source` (empty:
/// no ImageSets) the split each source's frames are listed in; labels as `options` say.
KittiExportSummary export_frames(const std::vector<SourceFrames>& sources, const std::vector<std::string>& split_of_source,
                                 nlohmann::json origin, const std::filesystem::path& out_dir,
                                 const KittiExportOptions& options, const ExportProgress& progress) {
    KittiExportSummary summary;
    summary.out = checked_output_dir(out_dir, kitti_layout());
    std::vector<std::filesystem::path> pcds;
    for (const auto& source : sources) pcds.insert(pcds.end(), source.pcds.begin(), source.pcds.end());
    const float largest = largest_intensity(pcds, progress.intensity_scanned);
    summary.intensity_scale = largest > 0.0f ? largest : 1.0f;

    const StagingDir staging_lock(summary.out);
    staging_lock.clear();
    const std::filesystem::path& staging = staging_lock.path();
    for (const char* d : {"velodyne", "label_2", "calib"}) std::filesystem::create_directories(staging / "training" / d);
    nlohmann::json frames = nlohmann::json::array();
    std::map<std::string, std::string> image_sets;
    std::size_t k = 0;
    for (std::size_t s = 0; s < sources.size(); ++s) {
        const SourceFrames& source = sources[s];
        for (std::size_t i = 0; i < source.pcds.size(); ++i, ++k) {
            const std::vector<Return> returns = read_frame_pcd(source.pcds[i]);
            const std::string stem = frame_file_stem(k);
            write_text(staging / "training" / "velodyne" / (stem + ".bin"), velodyne_bytes(returns, summary.intensity_scale));
            nlohmann::json entry = {{"kitti", stem}, {"pcd", "frames/" + source.pcds[i].filename().string()}, {"returns", returns.size()}};
            if (sources.size() > 1 || !split_of_source.empty()) entry["dataset"] = s;
            std::vector<Label> labels;
            if (source.truth[i]) {
                labels = frame_labels(source.truth[i]->objects, returns, options);
                entry["frame_index"] = source.truth[i]->index;
            }
            std::string text;
            entry["labels"] = nlohmann::json::array();
            for (const auto& label : labels) {
                text += label.line + "\n";
                entry["labels"].push_back(label.record);
            }
            write_text(staging / "training" / "label_2" / (stem + ".txt"), text);
            frames.push_back(std::move(entry));
            summary.labels += labels.size();
            write_text(staging / "training" / "calib" / (stem + ".txt"), kitti_calib_text());
            summary.returns += returns.size();
            if (!split_of_source.empty()) image_sets[split_of_source[s]] += stem + "\n";
            if (progress.frame_written) progress.frame_written(static_cast<int>(k + 1), static_cast<int>(pcds.size()));
        }
    }
    if (!split_of_source.empty()) {
        std::filesystem::create_directories(staging / "ImageSets");
        for (const char* split : {"train", "val", "test"}) write_text(staging / "ImageSets" / (std::string(split) + ".txt"), image_sets[split]);
    }
    summary.frames = static_cast<int>(k);
    write_json(staging / "ladarsim_export.json", export_record(std::move(origin), summary.intensity_scale, options, std::move(frames)));
    summary.kept = swap_in_output(staging, summary.out);
    return summary;
}

/// The heading of an upright box about a ground-truth box, and its axes in the velodyne frame:
/// along it, across it (to its left), up.
struct Heading {
    double yaw = 0.0;
    Eigen::Matrix3d axes;  ///< columns: along, across, up
};

/// The box's nose (own x axis) projected onto the horizontal plane, or its left axis turned back
/// a quarter when the nose points straight up or down.
Heading heading_of(const OrientedBox& box) {
    const Eigen::Matrix3d axes = box.orientation.normalized().toRotationMatrix();
    const Eigen::Vector3d nose = axes.col(0), left = axes.col(1);
    Heading h;
    h.yaw = std::hypot(nose.x(), nose.y()) > 1e-9 ? std::atan2(nose.y(), nose.x()) : std::atan2(left.y(), left.x()) - kPi / 2;
    h.axes << std::cos(h.yaw), -std::sin(h.yaw), 0.0, std::sin(h.yaw), std::cos(h.yaw), 0.0, 0.0, 0.0, 1.0;
    return h;
}

/// Extents of the upright box about `box` along the heading's axes: its three edges projected on each.
Eigen::Vector3d upright_extents(const OrientedBox& box, const Heading& h) {
    const Eigen::Matrix3d axes = box.orientation.normalized().toRotationMatrix();
    return (h.axes.transpose() * axes).cwiseAbs() * box.size;
}

/// The KITTI box of the upright box about `centre` (velodyne frame) with `extents` along the
/// heading's axes.
KittiBox kitti_box_of(const Eigen::Vector3d& centre, const Eigen::Vector3d& extents, double yaw) {
    KittiBox k;
    k.length_m = extents.x();
    k.width_m = extents.y();
    k.height_m = extents.z();
    k.bottom_centre_camera = camera_from_velodyne(centre - Eigen::Vector3d(0.0, 0.0, k.height_m / 2));
    // A nose along velodyne (cos yaw, sin yaw, 0) is camera (-sin yaw, 0, cos yaw), which KITTI's
    // roty(ry) makes of its +x when ry = -yaw - pi/2.
    k.rotation_y_rad = wrapped(-yaw - kPi / 2);
    k.alpha_rad = wrapped(k.rotation_y_rad - std::atan2(k.bottom_centre_camera.x(), k.bottom_centre_camera.z()));
    return k;
}

}  // namespace

KittiBox kitti_box(const OrientedBox& box_sensor) {
    const Heading h = heading_of(box_sensor);
    return kitti_box_of(box_sensor.centre, upright_extents(box_sensor, h), h.yaw);
}

KittiBox kitti_label_box(const OrientedBox& box_sensor, const std::vector<Eigen::Vector3d>& returns) {
    const Heading h = heading_of(box_sensor);
    // The faces along the heading's axes, relative to ground truth's centre, pushed out to hold each return.
    Eigen::Vector3d high = upright_extents(box_sensor, h) / 2, low = -high;
    for (const Eigen::Vector3d& p : returns) {
        const Eigen::Vector3d local = h.axes.transpose() * (p - box_sensor.centre);
        high = high.cwiseMax((local.array() + kKittiLabelMargin_m).matrix());
        low = low.cwiseMin((local.array() - kKittiLabelMargin_m).matrix());
    }
    return kitti_box_of(box_sensor.centre + h.axes * ((high + low) / 2), high - low, h.yaw);
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
        [](const std::string& name) { return name == "training" || name == "ImageSets" || name == "ladarsim_export.json"; },
        [](const std::string& relative) {
            static const std::regex own(
                R"(training/(velodyne|label_2|calib)|training/velodyne/\d{6,}\.bin(\.tmp)?|training/(label_2|calib)/\d{6,}\.txt(\.tmp)?)"
                R"(|ImageSets/(train|val|test)\.txt(\.tmp)?)");
            return std::regex_match(relative, own);
        }};
    return layout;
}

KittiExportSummary export_kitti(const std::filesystem::path& dataset_dir, const std::filesystem::path& out_dir,
                                const KittiExportOptions& options, const ExportProgress& progress) {
    const SourceFrames source = read_source(dataset_dir);
    const nlohmann::json origin = {{"exported_from", source.dir.string()}, {"dataset_id", source.manifest.id}};
    return export_frames({source}, {}, origin, out_dir, options, progress);
}

KittiExportSummary export_kitti(const std::filesystem::path& origin, const std::vector<KittiSource>& sources,
                                const std::filesystem::path& out_dir, const KittiExportOptions& options,
                                const ExportProgress& progress) {
    std::vector<SourceFrames> frames;
    std::vector<std::string> splits;
    nlohmann::json datasets = nlohmann::json::array();
    const std::filesystem::path from = std::filesystem::absolute(origin).lexically_normal();
    for (const KittiSource& s : sources) {
        if (s.split != "train" && s.split != "val" && s.split != "test")
            throw InputError(s.dataset_dir.string(), "split", "\"" + s.split + "\" is not one of: train, val, test");
        frames.push_back(read_source(s.dataset_dir));
        splits.push_back(s.split);
        datasets.push_back({{"directory", frames.back().dir.lexically_relative(from).string()},
                            {"dataset_id", frames.back().manifest.id},
                            {"split", s.split}});
    }
    const nlohmann::json record = {{"exported_from", from.string()}, {"datasets", datasets}};
    return export_frames(frames, splits, record, out_dir, options, progress);
}

}  // namespace ladarsim
