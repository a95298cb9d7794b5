#include "ladarsim/dataset/las_export.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <regex>

#include <Eigen/Geometry>

#include "ladarsim/core/input_error.h"
#include "ladarsim/core/json_fields.h"
#include "ladarsim/core/json_file.h"
#include "ladarsim/dataset/frame_io.h"
#include "ladarsim/dataset/intensity_scale.h"
#include "ladarsim/dataset/las_file.h"
#include "ladarsim/dataset/poses_file.h"

namespace ladarsim {

namespace {

constexpr std::uint8_t kNeverClassified = 0, kUnclassified = 1, kNoise = 7;
constexpr double kScale_m = 1e-4;  // 0.1 mm: below float32's rounding of a PCD's coordinates beyond 1.6 km
constexpr double kScanAngleUnit_deg = 0.006;

/// Where the sensor frame sits in the world: the mount's pose a render's manifest records, or a
/// moving sensor's at each return's own time (sensor_trajectory.txt).
struct MountPose {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
    std::vector<TimedPose> trajectory;  ///< a moving sensor's; empty for a fixed mount

    Eigen::Vector3d to_world(const Eigen::Vector3d& sensor, double time_s) const {
        return trajectory.empty() ? Eigen::Vector3d(orientation * sensor + position) : Eigen::Vector3d(pose_at(trajectory, time_s) * sensor);
    }
};

MountPose read_mount(const std::filesystem::path& manifest_file) {
    const nlohmann::json manifest = read_json(manifest_file);
    if (!manifest.contains("mount"))
        throw InputError(manifest_file.string(), "mount",
                         "missing: the dataset (a recording?) does not say where its sensor stood, so --world cannot place it");
    JsonFields mount(manifest.at("mount"), manifest_file.string(), "mount");
    MountPose pose;
    pose.position = mount.vec3("position_m");
    const auto& q = mount.array("orientation_wxyz");
    if (q.size() != 4 || !std::all_of(q.begin(), q.end(), [](const nlohmann::json& v) { return v.is_number(); }))
        mount.fail("orientation_wxyz", "is not an array of four numbers");
    pose.orientation = Eigen::Quaterniond(q[0].get<double>(), q[1].get<double>(), q[2].get<double>(), q[3].get<double>()).normalized();
    if (mount.boolean("moving_platform", false)) {
        const std::filesystem::path file = manifest_file.parent_path() / "sensor_trajectory.txt";
        std::error_code ec;
        if (!std::filesystem::exists(file, ec))
            throw InputError(file.string(), "(file)", "missing: the sensor moved, and --world needs its pose at each return's time");
        pose.trajectory = read_sensor_trajectory_txt(file);
        if (pose.trajectory.empty()) throw InputError(file.string(), "(file)", "holds no pose");
        pose.position = pose.trajectory.front().world_from_sensor.translation();
    }
    return pose;
}

/// Each object's class over the whole run (ground truth lists the scene's objects frame by frame);
/// nullopt without ground truth.
std::optional<std::map<std::uint32_t, std::string>> classes_of(const std::filesystem::path& dataset_dir) {
    const auto file = dataset_dir / "ground_truth.json";
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) return std::nullopt;
    std::map<std::uint32_t, std::string> classes = {{0u, "background"}};
    for (const auto& frame : read_ground_truth_json(file))
        for (const auto& o : frame.objects) classes[o.object_id] = o.object_class;
    return classes;
}

/// Returns per beam (column, row), for each return's number of returns.
std::map<std::pair<int, int>, int> returns_per_beam(const std::vector<Return>& returns) {
    std::map<std::pair<int, int>, int> counts;
    for (const Return& r : returns) ++counts[{r.column, r.row}];
    return counts;
}

LasCloud las_cloud(const std::vector<Return>& returns, const std::optional<std::map<std::uint32_t, std::string>>& classes,
                   float intensity_scale, const std::optional<MountPose>& world) {
    LasCloud cloud;
    cloud.system_identifier = "ladarsim";
    cloud.generating_software = std::string("ladarsim ") + LADARSIM_VERSION;
    cloud.scale = Eigen::Vector3d::Constant(kScale_m);
    if (world) cloud.offset = world->position.array().round().matrix();  // points near the sensor keep the int32 range
    cloud.extra_fields = {{"object_id", LasExtraField::Type::uint32, "ladarsim object id", true, static_cast<double>(kNoObject)},
                          {"intensity_pe", LasExtraField::Type::float32, "intensity, photo-electrons", false, 0.0}};
    const auto per_beam = returns_per_beam(returns);
    cloud.points.reserve(returns.size());
    for (const Return& r : returns) {
        LasPoint p;
        const Eigen::Vector3d sensor = r.position_sensor.cast<double>();
        p.position = world ? world->to_world(sensor, r.time_s) : sensor;
        p.intensity = static_cast<std::uint16_t>(std::lround(65535.0 * std::clamp(r.intensity / intensity_scale, 0.0f, 1.0f)));
        p.return_number = static_cast<std::uint8_t>(std::min(r.return_index + 1, 15));
        p.number_of_returns = static_cast<std::uint8_t>(std::clamp(per_beam.at({r.column, r.row}), 1, 15));
        std::optional<std::string> object_class;
        if (classes) {
            const auto it = classes->find(r.object_id);
            object_class = it == classes->end() ? std::string("unknown") : it->second;
        }
        p.classification = las_class_code(r.source, object_class);
        p.user_data = static_cast<std::uint8_t>(r.source);
        p.scan_angle = static_cast<std::int16_t>(std::lround(std::clamp(r.beam_az_rad * 180.0 / std::numbers::pi / kScanAngleUnit_deg, -30000.0, 30000.0)));
        p.gps_time = r.time_s;
        p.extra = {static_cast<double>(r.object_id), static_cast<double>(r.intensity)};
        cloud.points.push_back(std::move(p));
    }
    return cloud;
}

nlohmann::json export_record(const std::filesystem::path& source, bool world, float intensity_scale, nlohmann::json frames) {
    nlohmann::json class_map = nlohmann::json::object();
    for (const auto& [name, code] : las_class_map()) class_map[name] = code;
    return {{"software", software_json()},
            {"exported_from", source.string()},
            {"format", "LAS 1.4, point data record format 6, extra bytes object_id (uint32) and intensity_pe (float32)"},
            {"frame", world ? "world: the mount's pose in manifest.json applied, or a moving sensor's at each return's time from "
                              "sensor_trajectory.txt (ENU metres; X, Y, Z offsets the sensor position, where it started, rounded to metres)"
                            : "ladarsim's sensor frame: x forward, y left, z up, metres, sensor at the origin"},
            {"gps_time", "the return's time_s (its pulse's emission), seconds on the dataset's clock (a render's scenario "
                         "time, a recording's timestamps), not GPS time; global encoding bit 0 is 0"},
            {"intensity", {{"las", "round(65535 x intensity / scale), 0 when negative"}, {"scale", intensity_scale}}},
            {"classification", class_map},
            {"classification_notes", "false alarms 7 (noise) whatever their beam met; a recording without ground truth 0 (never classified)"},
            {"user_data", "the return's source: 0 surface, 1 volume backscatter, 2 false alarm"},
            {"scan_angle", "the beam's azimuth in the sensor frame, 0.006 deg units"},
            {"frames", std::move(frames)}};
}

}  // namespace

const std::vector<std::pair<std::string, int>>& las_class_map() {
    static const std::vector<std::pair<std::string, int>> map{
        {"background", kUnclassified}, {"terrain", 2}, {"tree", 5}, {"building", 6},
        {"drone", 64},                 {"bird", 65},   {"plane", 66}, {"cloud", 67}};
    return map;
}

std::uint8_t las_class_code(ReturnSource source, const std::optional<std::string>& object_class) {
    if (source == ReturnSource::false_alarm) return kNoise;
    if (!object_class) return kNeverClassified;
    for (const auto& [name, code] : las_class_map())
        if (name == *object_class) return static_cast<std::uint8_t>(code);
    return kUnclassified;
}

const OutputLayout& las_layout() {
    static const OutputLayout layout{"export",
                                     [](const std::string& name) {
                                         static const std::regex own(R"(\d{6,}\.las|ladarsim_export\.json)");
                                         return std::regex_match(name, own);
                                     },
                                     [](const std::string&) { return false; }};
    return layout;
}

LasExportSummary export_las(const std::filesystem::path& dataset_dir, const std::filesystem::path& out_dir,
                            const LasExportOptions& options, const ExportProgress& progress) {
    std::error_code ec;
    if (!std::filesystem::is_directory(dataset_dir, ec))
        throw InputError(dataset_dir.string(), "DIR", std::filesystem::exists(dataset_dir, ec) ? "is not a directory" : "no such directory");
    const std::filesystem::path source = std::filesystem::absolute(dataset_dir).lexically_normal();
    read_manifest(source / "manifest.json");  // a dataset says which sensor took it
    const std::optional<MountPose> world = options.world ? std::optional<MountPose>(read_mount(source / "manifest.json")) : std::nullopt;
    const auto pcds = frame_pcd_files(source);
    const auto classes = classes_of(source);

    LasExportSummary summary;
    summary.out = checked_output_dir(out_dir, las_layout());
    const float largest = largest_intensity(pcds, progress.intensity_scanned);
    summary.intensity_scale = largest > 0.0f ? largest : 1.0f;
    const StagingDir staging(summary.out);
    staging.clear();
    nlohmann::json frames = nlohmann::json::array();
    for (std::size_t i = 0; i < pcds.size(); ++i) {
        const std::vector<Return> returns = read_frame_pcd(pcds[i]);
        const std::string name = frame_file_stem(i) + ".las";
        write_las(staging.path() / name, las_cloud(returns, classes, summary.intensity_scale, world));
        frames.push_back({{"las", name}, {"pcd", "frames/" + pcds[i].filename().string()}, {"returns", returns.size()}});
        summary.returns += returns.size();
        if (progress.frame_written) progress.frame_written(static_cast<int>(i + 1), static_cast<int>(pcds.size()));
    }
    summary.frames = static_cast<int>(pcds.size());
    write_json(staging.path() / "ladarsim_export.json", export_record(source, options.world, summary.intensity_scale, std::move(frames)));
    summary.kept = swap_in_output(staging.path(), summary.out);
    return summary;
}

}  // namespace ladarsim
