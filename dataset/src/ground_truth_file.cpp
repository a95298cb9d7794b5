#include "ladarsim/dataset/ground_truth_file.h"

#include <cmath>
#include <limits>
#include <string>

#include "ladarsim/core/json_fields.h"
#include "ladarsim/core/json_file.h"

namespace ladarsim {

namespace {

constexpr double kAnyNumber = std::numeric_limits<double>::max();
constexpr long long kMaxUint32 = std::numeric_limits<std::uint32_t>::max();
/// A stored quaternion is a rounded unit quaternion; anything further off was not written by us.
constexpr double kUnitNormTolerance = 1e-6;

nlohmann::json box_json(const OrientedBox& box) {
    const Eigen::Quaterniond& q = box.orientation;
    return {{"centre_m", {box.centre.x(), box.centre.y(), box.centre.z()}},
            {"size_m", {box.size.x(), box.size.y(), box.size.z()}},
            {"orientation_wxyz", {q.w(), q.x(), q.y(), q.z()}}};
}

std::string indexed(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

nlohmann::json pose_json(const Eigen::Isometry3d& pose) {
    const Eigen::Vector3d t = pose.translation();
    const Eigen::Quaterniond q(pose.linear());
    return {{"position_m", {t.x(), t.y(), t.z()}}, {"orientation_wxyz", {q.w(), q.x(), q.y(), q.z()}}};
}

Eigen::Quaterniond read_quaternion(JsonFields& f) {
    const auto& q = f.array("orientation_wxyz");
    if (q.size() != 4) f.fail("orientation_wxyz", "expected an array of 4 numbers");
    double wxyz[4];
    for (std::size_t i = 0; i < 4; ++i) {
        if (!q[i].is_number()) f.fail("orientation_wxyz", "expected an array of 4 numbers");
        wxyz[i] = q[i].get<double>();
    }
    const Eigen::Quaterniond orientation(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
    if (!(std::abs(orientation.norm() - 1.0) <= kUnitNormTolerance)) f.fail("orientation_wxyz", "not a unit quaternion");
    return orientation;
}

Eigen::Isometry3d read_pose(JsonFields& parent, const std::string& key) {
    JsonFields f(parent.object(key), parent.file(), parent.path_of(key));
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = f.vec3("position_m");
    pose.linear() = read_quaternion(f).normalized().toRotationMatrix();
    f.reject_unknown_keys();
    return pose;
}

OrientedBox read_box(JsonFields& parent, const std::string& key) {
    JsonFields f(parent.object(key), parent.file(), parent.path_of(key));
    OrientedBox box;
    box.centre = f.vec3("centre_m");
    box.size = f.vec3("size_m");
    if ((box.size.array() < 0.0).any()) f.fail("size_m", "sizes must not be negative");
    box.orientation = read_quaternion(f);
    f.reject_unknown_keys();
    return box;
}

GroundTruthObject read_object(const nlohmann::json& json, const std::string& file, const std::string& path) {
    JsonFields f(json, file, path);
    GroundTruthObject o;
    o.object_id = static_cast<std::uint32_t>(f.integer("id", 0, kMaxUint32));
    o.object_class = f.string("class");
    o.name = f.string("name");
    o.time_s = f.number("time_s", -kAnyNumber, kAnyNumber);
    o.returns = static_cast<std::uint32_t>(f.integer("returns", 0, kMaxUint32));
    o.folded_returns = static_cast<std::uint32_t>(f.integer("folded_returns", 0, kMaxUint32, 0));
    o.saturated_returns = static_cast<std::uint32_t>(f.integer("saturated_returns", 0, kMaxUint32, 0));
    o.box_world = read_box(f, "box_world");
    o.box_sensor = read_box(f, "box_sensor");
    f.reject_unknown_keys();
    return o;
}

FrameGroundTruth read_frame(const nlohmann::json& json, const std::string& file, const std::string& path) {
    JsonFields f(json, file, path);
    FrameGroundTruth frame;
    frame.index = static_cast<std::uint64_t>(f.integer("index", 0, std::numeric_limits<long long>::max()));
    frame.start_time_s = f.number("start_time_s", -kAnyNumber, kAnyNumber);
    frame.end_time_s = f.number("end_time_s", frame.start_time_s, kAnyNumber);
    if (f.has("sensor_pose")) frame.sensor_pose = read_pose(f, "sensor_pose");
    const auto& objects = f.array("objects");
    for (std::size_t i = 0; i < objects.size(); ++i) {
        frame.objects.push_back(read_object(objects[i], file, indexed(f.path_of("objects"), i)));
    }
    f.reject_unknown_keys();
    return frame;
}

}  // namespace

nlohmann::json ground_truth_object_json(const GroundTruthObject& o) {
    return {{"id", o.object_id},       {"class", o.object_class},   {"name", o.name},
            {"time_s", o.time_s},      {"returns", o.returns},      {"folded_returns", o.folded_returns},
            {"saturated_returns", o.saturated_returns},
            {"box_world", box_json(o.box_world)}, {"box_sensor", box_json(o.box_sensor)}};
}

FrameGroundTruth ground_truth_of(const Frame& frame) {
    return {frame.index, frame.start_time_s, frame.end_time_s, frame.ground_truth, frame.sensor_pose};
}

void write_ground_truth_json(const std::filesystem::path& path, const std::vector<FrameGroundTruth>& frames) {
    nlohmann::json frames_json = nlohmann::json::array();
    for (const auto& frame : frames) {
        nlohmann::json objects = nlohmann::json::array();
        for (const auto& o : frame.objects) objects.push_back(ground_truth_object_json(o));
        nlohmann::json entry = {{"index", frame.index}, {"start_time_s", frame.start_time_s}, {"end_time_s", frame.end_time_s}};
        if (frame.sensor_pose) entry["sensor_pose"] = pose_json(*frame.sensor_pose);
        entry["objects"] = std::move(objects);
        frames_json.push_back(std::move(entry));
    }
    write_json(path, {{"frames", std::move(frames_json)}});
}

std::vector<FrameGroundTruth> read_ground_truth_json(const std::filesystem::path& path) {
    const std::string file = path.string();
    const nlohmann::json json = read_json(path);
    JsonFields top(json, file, "");
    const auto& frames_json = top.array("frames");
    std::vector<FrameGroundTruth> frames;
    for (std::size_t i = 0; i < frames_json.size(); ++i) {
        frames.push_back(read_frame(frames_json[i], file, indexed("frames", i)));
    }
    top.reject_unknown_keys();
    return frames;
}

}  // namespace ladarsim
