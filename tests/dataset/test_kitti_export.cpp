// KITTI export: label boxes against the KITTI devkit's own box construction (compute_box_3d
// taken back to the velodyne frame), closed forms for turned boxes, the calib, and which files
// of an export directory are ladarsim's.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "ladarsim/core/input_error.h"
#include "ladarsim/dataset/kitti_export.h"
#include "../support/input_error_of.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// The eight corners as the devkit's compute_box_3d builds them in the camera frame, taken to the
/// velodyne frame by the inverse of the standard permutation (velo x = cam z, y = -cam x, z = -cam y).
std::array<Eigen::Vector3d, 8> devkit_corners_velodyne(const KittiBox& k) {
    std::array<Eigen::Vector3d, 8> corners;
    const double c = std::cos(k.rotation_y_rad), s = std::sin(k.rotation_y_rad);
    int i = 0;
    for (double x : {k.length_m / 2, -k.length_m / 2})
        for (double y : {0.0, -k.height_m})
            for (double z : {k.width_m / 2, -k.width_m / 2}) {
                const Eigen::Vector3d cam = Eigen::Vector3d(c * x + s * z, y, -s * x + c * z) + k.bottom_centre_camera;
                corners[i++] = Eigen::Vector3d(cam.z(), -cam.x(), -cam.y());
            }
    return corners;
}

std::array<Eigen::Vector3d, 8> box_corners(const OrientedBox& box) {
    std::array<Eigen::Vector3d, 8> corners;
    int i = 0;
    for (double x : {-0.5, 0.5})
        for (double y : {-0.5, 0.5})
            for (double z : {-0.5, 0.5})
                corners[i++] = box.centre + box.orientation * Eigen::Vector3d(x, y, z).cwiseProduct(box.size);
    return corners;
}

/// Turned as scenario files turn objects: Rz(yaw) * Ry(-pitch) * Rx(roll).
Eigen::Quaterniond aircraft(double yaw_deg, double pitch_deg, double roll_deg) {
    const double d = kPi / 180;
    return Eigen::AngleAxisd(yaw_deg * d, Eigen::Vector3d::UnitZ()) *
           Eigen::AngleAxisd(-pitch_deg * d, Eigen::Vector3d::UnitY()) *
           Eigen::AngleAxisd(roll_deg * d, Eigen::Vector3d::UnitX());
}

}  // namespace

TEST_CASE("a box turned about the vertical only has the devkit build the same eight corners", "[kitti_export]") {
    for (const double yaw_deg : {0.0, 30.0, 90.0, 179.0, -120.0}) {
        OrientedBox box;
        box.centre = {12.0, -5.0, 0.5};
        box.size = {4.0, 2.4, 3.0};
        box.orientation = aircraft(yaw_deg, 0, 0);
        const KittiBox k = kitti_box(box);
        CHECK(k.length_m == Approx(4.0));
        CHECK(k.width_m == Approx(2.4));
        CHECK(k.height_m == Approx(3.0));
        // Bottom centre, camera frame: x = -y, y = -(z - h/2), z = x.
        CHECK(k.bottom_centre_camera.isApprox(Eigen::Vector3d(5.0, 1.0, 12.0), 1e-12));
        CHECK(std::remainder(k.rotation_y_rad - (-yaw_deg * kPi / 180 - kPi / 2), 2 * kPi) == Approx(0.0).margin(1e-12));
        CHECK(k.rotation_y_rad >= -kPi);
        CHECK(k.rotation_y_rad < kPi);
        CHECK(k.alpha_rad == Approx(std::remainder(k.rotation_y_rad - std::atan2(5.0, 12.0), 2 * kPi)));
        const auto truth = box_corners(box);
        for (const auto& corner : devkit_corners_velodyne(k)) {
            double nearest = 1e9;
            for (const auto& t : truth) nearest = std::min(nearest, (t - corner).norm());
            CHECK(nearest < 1e-9);
        }
    }
}

TEST_CASE("a tilted box becomes the tightest box about the vertical that holds it", "[kitti_export]") {
    const double c = std::cos(20 * kPi / 180), s = std::sin(20 * kPi / 180);
    struct Case {
        const char* what;
        Eigen::Quaterniond orientation;
        double length_m, width_m, height_m, rotation_y_rad;
    };
    // A 4 x 2 x 1 m box (l, w, h in its own frame).
    const Case cases[] = {
        {"rolled a quarter: width and height trade places", aircraft(30, 0, 90), 4, 1, 2, -30 * kPi / 180 - kPi / 2},
        {"nose straight up: the heading comes from the left axis", aircraft(30, 90, 0), 1, 2, 4, -30 * kPi / 180 - kPi / 2},
        {"pitched: l cos + h sin along the heading, h cos + l sin upright", aircraft(-50, 20, 0), 4 * c + 1 * s, 2,
         1 * c + 4 * s, 50 * kPi / 180 - kPi / 2},
    };
    for (const Case& test : cases) {
        INFO(test.what);
        OrientedBox box;
        box.size = {4.0, 2.0, 1.0};
        box.orientation = test.orientation;
        const KittiBox k = kitti_box(box);
        CHECK(k.length_m == Approx(test.length_m));
        CHECK(k.width_m == Approx(test.width_m));
        CHECK(k.height_m == Approx(test.height_m));
        CHECK(k.rotation_y_rad == Approx(test.rotation_y_rad));
    }
}

TEST_CASE("targets keep their names as label types, and the scene is not labelled", "[kitti_export]") {
    CHECK(kitti_type("drone") == "Drone");
    CHECK(kitti_type("bird") == "Bird");
    CHECK(kitti_type("plane") == "Plane");
    for (const char* scene : {"building", "terrain", "tree", "cloud", "background"}) CHECK_FALSE(kitti_type(scene));
}

TEST_CASE("a label line has KITTI's 15 fields in order, with no image box", "[kitti_export]") {
    KittiBox k;
    k.height_m = 3, k.width_m = 2.4, k.length_m = 4, k.bottom_centre_camera = {-5, 1, 12};
    k.rotation_y_rad = -2.0, k.alpha_rad = -1.5;
    std::istringstream line(kitti_label_line("Plane", k));
    std::string type;
    double v[14];
    line >> type;
    for (double& x : v) line >> x;
    CHECK(line);
    std::string rest;
    CHECK_FALSE(line >> rest);
    CHECK(type == "Plane");
    const double expected[14] = {0, 3, -1.5, -1, -1, -1, -1, 3, 2.4, 4, -5, 1, 12, -2.0};
    for (int i = 0; i < 14; ++i) CHECK(v[i] == Approx(expected[i]));
}

TEST_CASE("the calib takes velodyne to camera by the standard permutation", "[kitti_export]") {
    std::istringstream text(kitti_calib_text());
    std::map<std::string, std::vector<double>> calib;
    for (std::string line; std::getline(text, line);) {
        std::istringstream fields(line);
        std::string key;
        fields >> key;
        for (double x; fields >> x;) calib[key].push_back(x);
    }
    for (const char* p : {"P0:", "P1:", "P2:", "P3:", "Tr_imu_to_velo:"})
        CHECK(calib[p] == std::vector<double>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0});
    CHECK(calib["R0_rect:"] == std::vector<double>{1, 0, 0, 0, 1, 0, 0, 0, 1});
    const auto& tr = calib["Tr_velo_to_cam:"];
    REQUIRE(tr.size() == 12);
    const auto camera = [&](double x, double y, double z) {
        return Eigen::Vector3d(tr[0] * x + tr[1] * y + tr[2] * z + tr[3], tr[4] * x + tr[5] * y + tr[6] * z + tr[7],
                               tr[8] * x + tr[9] * y + tr[10] * z + tr[11]);
    };
    CHECK(camera(1, 0, 0) == Eigen::Vector3d(0, 0, 1));   // forward is the camera's z
    CHECK(camera(0, 1, 0) == Eigen::Vector3d(-1, 0, 0));  // left is the camera's -x
    CHECK(camera(0, 0, 1) == Eigen::Vector3d(0, -1, 0));  // up is the camera's -y
}

TEST_CASE("an export directory is replaced only where ladarsim wrote it", "[kitti_export]") {
    const test::ScratchDir dir;
    const auto out = dir / "kitti";
    std::filesystem::create_directories(out / "training" / "velodyne");
    std::ofstream(out / "training" / "velodyne" / "000000.bin") << "ours";
    std::ofstream(out / "ladarsim_export.json") << "{}";
    std::ofstream(out / kOwnedList) << "training\nladarsim_export.json\n";
    std::ofstream(out / "NOTES.txt") << "theirs";
    CHECK(checked_output_dir(out, kitti_layout()) == out);
    std::filesystem::create_directories(out / "training" / "image_2");
    const InputError e = test::input_error_of([&] { checked_output_dir(out, kitti_layout()); });
    CHECK(e.field() == "--out");
    CHECK_THAT(e.problem(), Catch::Contains("training/image_2/"));
    std::filesystem::remove(out / "training" / "image_2");
    std::ofstream(out / "training" / "velodyne" / "notes.txt") << "theirs";
    CHECK_THAT(test::input_error_of([&] { checked_output_dir(out, kitti_layout()); }).problem(),
               Catch::Contains("training/velodyne/notes.txt"));
    std::filesystem::remove(out / kOwnedList);
    std::filesystem::remove(out / "training" / "velodyne" / "notes.txt");
    CHECK_THAT(test::input_error_of([&] { checked_output_dir(out, kitti_layout()); }).problem(),
               Catch::Contains("refusing to replace"));
}
