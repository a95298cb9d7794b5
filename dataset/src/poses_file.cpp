#include "ladarsim/dataset/poses_file.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "ladarsim/core/atomic_file.h"
#include "ladarsim/core/input_error.h"

namespace ladarsim {

void write_poses_txt(const std::filesystem::path& path, const std::vector<Eigen::Isometry3d>& world_from_sensor) {
    AtomicFile out(path);
    char number[32];
    for (const Eigen::Isometry3d& pose : world_from_sensor) {
        const Eigen::Matrix<double, 3, 4> m = pose.matrix().topRows<3>();
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) {
                // Shortest round-trip form: the numbers read back to the same doubles.
                const auto end = std::to_chars(number, number + sizeof number, m(r, c)).ptr;
                out.stream().write(number, end - number);
                out.stream().put(r == 2 && c == 3 ? '\n' : ' ');
            }
    }
    out.commit();
}

std::vector<Eigen::Isometry3d> read_poses_txt(const std::filesystem::path& path) {
    const std::string file = path.string();
    std::ifstream in(path);
    if (!in) throw InputError(file, "(file)", "cannot be opened");
    std::vector<Eigen::Isometry3d> poses;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        std::istringstream values(line);
        Eigen::Matrix<double, 3, 4> m;
        const std::string where = "line " + std::to_string(number);
        for (int k = 0; k < 12; ++k)
            if (!(values >> m(k / 4, k % 4)) || !std::isfinite(m(k / 4, k % 4)))
                throw InputError(file, where, "expected 12 finite numbers (a 3 x 4 world-from-sensor matrix, row by row)");
        if (std::string rest; values >> rest) throw InputError(file, where, "has more than 12 numbers");
        const Eigen::Matrix3d r = m.leftCols<3>();
        if (!(r.transpose() * r).isIdentity(1e-6) || r.determinant() < 0.0)
            throw InputError(file, where, "its 3 x 3 part is not a rotation");
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.linear() = r;
        pose.translation() = m.col(3);
        poses.push_back(pose);
    }
    return poses;
}

}  // namespace ladarsim
