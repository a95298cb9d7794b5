#include "ladarsim/dataset/poses_file.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "ladarsim/core/atomic_file.h"
#include "ladarsim/core/input_error.h"

namespace ladarsim {

namespace {

/// Shortest round-trip form: the number reads back to the same double.
void write_number(std::ostream& out, double value, char after) {
    char number[32];
    const auto end = std::to_chars(number, number + sizeof number, value).ptr;
    out.write(number, end - number);
    out.put(after);
}

void write_matrix(std::ostream& out, const Eigen::Isometry3d& pose) {
    const Eigen::Matrix<double, 3, 4> m = pose.matrix().topRows<3>();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) write_number(out, m(r, c), r == 2 && c == 3 ? '\n' : ' ');
}

/// The 3 x 4 matrix that follows in `values`, and nothing after it (a line of `numbers` in all).
Eigen::Isometry3d read_matrix(std::istringstream& values, const std::string& file, const std::string& where, const char* layout,
                              int numbers) {
    Eigen::Matrix<double, 3, 4> m;
    for (int k = 0; k < 12; ++k)
        if (!(values >> m(k / 4, k % 4)) || !std::isfinite(m(k / 4, k % 4))) throw InputError(file, where, layout);
    if (std::string rest; values >> rest) throw InputError(file, where, "has more than " + std::to_string(numbers) + " numbers");
    const Eigen::Matrix3d r = m.leftCols<3>();
    if (!(r.transpose() * r).isIdentity(1e-6) || r.determinant() < 0.0) throw InputError(file, where, "its 3 x 3 part is not a rotation");
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = r;
    pose.translation() = m.col(3);
    return pose;
}

/// Calls `line(values, where)` for each line of the file.
template <class Line>
void for_each_line(const std::filesystem::path& path, Line line) {
    std::ifstream in(path);
    if (!in) throw InputError(path.string(), "(file)", "cannot be opened");
    std::string text;
    for (int number = 1; std::getline(in, text); ++number) {
        std::istringstream values(text);
        line(values, "line " + std::to_string(number));
    }
}

}  // namespace

void write_poses_txt(const std::filesystem::path& path, const std::vector<Eigen::Isometry3d>& world_from_sensor) {
    AtomicFile out(path);
    for (const Eigen::Isometry3d& pose : world_from_sensor) write_matrix(out.stream(), pose);
    out.commit();
}

std::vector<Eigen::Isometry3d> read_poses_txt(const std::filesystem::path& path) {
    std::vector<Eigen::Isometry3d> poses;
    for_each_line(path, [&](std::istringstream& values, const std::string& where) {
        poses.push_back(read_matrix(values, path.string(), where, "12 finite numbers (a 3 x 4 world-from-sensor matrix, row by row)", 12));
    });
    return poses;
}

void write_sensor_trajectory_txt(const std::filesystem::path& path, const std::vector<TimedPose>& poses) {
    AtomicFile out(path);
    for (const TimedPose& p : poses) {
        write_number(out.stream(), p.time_s, ' ');
        write_matrix(out.stream(), p.world_from_sensor);
    }
    out.commit();
}

std::vector<TimedPose> read_sensor_trajectory_txt(const std::filesystem::path& path) {
    const std::string file = path.string();
    const char* layout = "13 finite numbers (a time, then a 3 x 4 world-from-sensor matrix, row by row)";
    std::vector<TimedPose> poses;
    for_each_line(path, [&](std::istringstream& values, const std::string& where) {
        TimedPose p;
        if (!(values >> p.time_s) || !std::isfinite(p.time_s)) throw InputError(file, where, layout);
        if (!poses.empty() && !(p.time_s > poses.back().time_s)) throw InputError(file, where, "its time is not after the line before's");
        p.world_from_sensor = read_matrix(values, file, where, layout, 13);
        poses.push_back(p);
    });
    return poses;
}

Eigen::Isometry3d pose_at(const std::vector<TimedPose>& poses, double time_s) {
    if (time_s <= poses.front().time_s) return poses.front().world_from_sensor;
    if (time_s >= poses.back().time_s) return poses.back().world_from_sensor;
    const auto after = std::upper_bound(poses.begin(), poses.end(), time_s, [](double t, const TimedPose& p) { return t < p.time_s; });
    const TimedPose& a = *(after - 1);
    const TimedPose& b = *after;
    const double u = (time_s - a.time_s) / (b.time_s - a.time_s);
    const Eigen::Quaterniond qa(a.world_from_sensor.linear()), qb(b.world_from_sensor.linear());
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = qa.slerp(u, qb).toRotationMatrix();
    pose.translation() = (1.0 - u) * a.world_from_sensor.translation() + u * b.world_from_sensor.translation();
    return pose;
}

}  // namespace ladarsim
