// poses.txt: KITTI odometry's layout read back to the same doubles; malformed lines refused.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <string>

#include "ladarsim/core/input_error.h"
#include "ladarsim/dataset/poses_file.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;
using Catch::Matchers::Contains;

TEST_CASE("poses_file: poses read back to the same doubles, one line of 12 numbers each", "[poses_file]") {
    const test::ScratchDir dir;
    std::vector<Eigen::Isometry3d> poses;
    for (int k = 0; k < 5; ++k) {
        Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
        p.linear() = Eigen::AngleAxisd(0.1 + 0.7 * k, Eigen::Vector3d(1.0, -2.0, 0.5 * k).normalized()).toRotationMatrix();
        p.translation() = Eigen::Vector3d(1e5 + 0.1 * k, -3.25e-7 * k, 123.456789 * k);
        poses.push_back(p);
    }
    write_poses_txt(dir / "poses.txt", poses);
    std::ifstream in(dir / "poses.txt");
    int lines = 0;
    for (std::string line; std::getline(in, line); ++lines) {
        std::istringstream words(line);
        int numbers = 0;
        for (double v; words >> v;) ++numbers;
        CHECK(numbers == 12);
    }
    CHECK(lines == 5);
    const auto back = read_poses_txt(dir / "poses.txt");
    REQUIRE(back.size() == poses.size());
    for (std::size_t k = 0; k < poses.size(); ++k) CHECK(back[k].matrix() == poses[k].matrix());
}

TEST_CASE("poses_file: a line that is not a rigid 3 x 4 pose is refused naming the line", "[poses_file]") {
    const test::ScratchDir dir;
    const auto refused = [&](const std::string& text, const std::string& problem) {
        std::ofstream(dir / "poses.txt") << text;
        CHECK_THROWS_WITH(read_poses_txt(dir / "poses.txt"), Contains("poses.txt") && Contains("line 2") && Contains(problem));
    };
    const std::string good = "1 0 0 0 0 1 0 0 0 0 1 0\n";
    refused(good + "1 0 0 0 0 1 0 0 0 0 1\n", "12 finite numbers");
    refused(good + "1 0 0 0 0 1 0 0 0 0 1 0 7\n", "more than 12");
    refused(good + "2 0 0 0 0 1 0 0 0 0 1 0\n", "not a rotation");
    refused(good + "1 0 0 0 0 1 0 0 0 0 -1 0\n", "not a rotation");
    refused(good + "1 0 0 nan 0 1 0 0 0 0 1 0\n", "12 finite numbers");
}
