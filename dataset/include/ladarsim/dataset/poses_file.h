#pragma once
// The sensor's pose per frame in KITTI odometry's layout (poses.txt): one line a frame, the 3 x 4
// world-from-sensor matrix [R | t] row by row, 12 numbers separated by spaces. A frame's points
// (sensor frame) times its pose are in world coordinates.
#include <filesystem>
#include <vector>

#include <Eigen/Geometry>

namespace ladarsim {

/// Writes one line per pose, each number with the digits that read back to the same double.
void write_poses_txt(const std::filesystem::path& path, const std::vector<Eigen::Isometry3d>& world_from_sensor);

/// Reads a poses.txt. Throws InputError naming the file and the line for a line that is not 12
/// finite numbers or whose rotation is not orthonormal (to 1e-6).
std::vector<Eigen::Isometry3d> read_poses_txt(const std::filesystem::path& path);

/// A sensor's pose at one time (seconds, the frames' clock).
struct TimedPose {
    double time_s = 0.0;
    Eigen::Isometry3d world_from_sensor = Eigen::Isometry3d::Identity();
};

/// sensor_trajectory.txt, a moving sensor's pose over time for motion compensation: one line a
/// sample, its time then the 3 x 4 matrix as in poses.txt (13 numbers), times increasing.
void write_sensor_trajectory_txt(const std::filesystem::path& path, const std::vector<TimedPose>& poses);
/// Throws InputError naming the file and line, as read_poses_txt, and for a time not after the
/// line before's.
std::vector<TimedPose> read_sensor_trajectory_txt(const std::filesystem::path& path);
/// The pose at `time_s` between the samples around it: position linear, rotation by slerp;
/// clamped to the first and last. `poses` must not be empty.
Eigen::Isometry3d pose_at(const std::vector<TimedPose>& poses, double time_s);

}  // namespace ladarsim
