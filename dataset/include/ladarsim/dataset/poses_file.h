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

}  // namespace ladarsim
