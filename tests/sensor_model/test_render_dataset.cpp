// render_dataset's manifest, as readers of a dataset take it: the sensor's geometry (divergence
// the wider axis) and the gimbal's pointing for every frame.
#include <catch2/catch.hpp>

#include <algorithm>

#include "ladarsim/dataset/manifest.h"
#include "ladarsim/sensor_model/render/render_dataset.h"
#include "ladarsim/dataset/frame_pcd.h"
#include "ladarsim/dataset/poses_file.h"
#include "ladarsim/scene/procedural_models.h"
#include "../support/closed_form_scenario.h"
#include "../support/scene_builders.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;
using namespace ladarsim::sensor_model;

TEST_CASE("a rendered dataset's manifest says which sensor took it, as read_manifest reads it", "[render_dataset]") {
    const test::ScratchDir dir;
    Scenario s = test::closed_form_scenario();
    s.file = dir / "scenario.json";  // the manifest records where the scenario came from
    SECTION("the paper's LADAR, its beam wider in elevation") { s.sensor.transmitter.divergence_el_mrad = 0.9; }
    SECTION("the VLP-16") { s.sensor = sensor_preset("velodyne_vlp16"); }
    DatasetOptions options;
    options.out_dir = dir / "d";
    options.frames = 2;
    render_dataset(s, options);
    const Manifest m = read_manifest(dir / "d" / "manifest.json");
    const ScanPattern& scan = *s.sensor.scan;
    CHECK(m.sensor.beams_az == scan.columns());
    CHECK(m.sensor.beams_el == scan.rows());
    CHECK(m.sensor.field_az_deg == Approx(scan.field_az_deg()).epsilon(1e-15));
    CHECK(m.sensor.field_el_deg == Approx(scan.field_el_deg()).epsilon(1e-15));
    CHECK(m.sensor.divergence_mrad == std::max(s.sensor.transmitter.divergence_mrad, s.sensor.transmitter.divergence_el_mrad));
    REQUIRE(m.pointing.size() == 2);
    CHECK(m.pointing[0]);
    CHECK(m.pointing[1]);
}

TEST_CASE("the initial map holds the static world only: a drone hovering still is not in it", "[render_dataset]") {
    const test::ScratchDir dir;
    Scenario s = test::closed_form_scenario();
    s.file = dir / "scenario.json";
    // A wall 300 m ahead, and a drone-sized plate hovering still 100 m ahead, both in the field.
    scene::SceneObject wall = test::object_at(1, test::plate(40.0, 0.3), test::fixed_at(300.0, 0.0, 0.0));
    wall.object_class = scene::ObjectClass::building;
    scene::SceneObject drone = test::object_at(2, test::plate(0.5, 0.3), test::fixed_at(100.0, 0.0, 0.0));
    drone.object_class = scene::ObjectClass::drone;
    s.scene.objects = {wall, drone};
    DatasetOptions options;
    options.out_dir = dir / "d";
    options.frames = 1;
    render_dataset(s, options);
    const std::vector<Return> map = read_frame_pcd(dir / "d" / "background.pcd");
    const auto near_drone = std::count_if(map.begin(), map.end(), [](const Return& r) { return r.range_m < 200.0; });
    const auto on_wall = std::count_if(map.begin(), map.end(), [](const Return& r) { return r.range_m > 299.0; });
    CHECK(near_drone == 0);
    CHECK(on_wall > 100);
    // The frame itself sees the drone.
    const std::vector<Return> frame = read_frame_pcd(dir / "d" / "frames" / "000000.pcd");
    CHECK(std::count_if(frame.begin(), frame.end(), [](const Return& r) { return r.object_id == 2; }) > 0);
}

TEST_CASE("poses.txt holds the sensor's world-from-sensor pose, which takes a frame's points onto the world's wall", "[render_dataset]") {
    const test::ScratchDir dir;
    Scenario s = test::closed_form_scenario();
    s.file = dir / "scenario.json";
    s.render.noise = false;
    // The sensor at (5, -3, 2) turned 90 deg to the left: its +x looks along the world's +y, at a
    // wall 300 m away facing it.
    s.mount.position_world = {5.0, -3.0, 2.0};
    s.mount.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.5 * 3.14159265358979323846, Eigen::Vector3d::UnitZ()));
    scene::SceneObject wall = test::object_at(
        1, test::plate(40.0, 0.3),
        scene::Trajectory::fixed(scene::Pose{{5.0, 297.0, 2.0}, Eigen::Quaterniond(Eigen::AngleAxisd(0.5 * 3.14159265358979323846, Eigen::Vector3d::UnitZ()))}),
        scene::ObjectClass::building);
    s.scene.objects = {wall};
    DatasetOptions options;
    options.out_dir = dir / "d";
    options.frames = 2;
    render_dataset(s, options);
    const std::vector<Eigen::Isometry3d> poses = read_poses_txt(dir / "d" / "poses.txt");
    REQUIRE(poses.size() == 2);
    Eigen::Matrix<double, 3, 4> expected;
    expected << 0, -1, 0, 5,
                1, 0, 0, -3,
                0, 0, 1, 2;
    for (const auto& pose : poses) CHECK((pose.matrix().topRows<3>() - expected).cwiseAbs().maxCoeff() < 1e-12);
    const std::vector<Return> frame = read_frame_pcd(dir / "d" / "frames" / "000001.pcd");
    REQUIRE(frame.size() > 100);
    for (const Return& r : frame) {
        const Eigen::Vector3d world = poses[1] * r.position_sensor.cast<double>();
        CHECK(world.y() == Approx(297.0).margin(0.01));
        CHECK(std::abs(world.x() - 5.0) < 20.0);
        CHECK(std::abs(world.z() - 2.0) < 20.0);
    }
}

TEST_CASE("the initial map is surveyed on a clear day: a cloud volume in view is not in it", "[render_dataset]") {
    const test::ScratchDir dir;
    Scenario s = test::closed_form_scenario();
    s.file = dir / "scenario.json";
    // A wall 300 m ahead seen through a 40 m cloud (20 /km) centred 150 m ahead, filling the field.
    scene::SceneObject wall = test::object_at(1, test::plate(40.0, 0.3), test::fixed_at(300.0, 0.0, 0.0));
    wall.object_class = scene::ObjectClass::building;
    scene::SceneObject cloud =
        test::object_at(40, std::make_shared<scene::Model>(scene::make_cloud(40.0, 0.02)), test::fixed_at(150.0, 0.0, 0.0));
    cloud.object_class = scene::ObjectClass::cloud;
    s.scene.objects = {wall, cloud};
    DatasetOptions options;
    options.out_dir = dir / "d";
    options.frames = 1;
    render_dataset(s, options);
    const std::vector<Return> map = read_frame_pcd(dir / "d" / "background.pcd");
    const auto in_cloud = std::count_if(map.begin(), map.end(), [](const Return& r) { return r.range_m < 200.0; });
    const auto on_wall = std::count_if(map.begin(), map.end(), [](const Return& r) { return r.range_m > 299.0; });
    CHECK(in_cloud == 0);
    CHECK(on_wall > 100);
    // The frame itself sees the cloud's backscatter.
    const std::vector<Return> frame = read_frame_pcd(dir / "d" / "frames" / "000000.pcd");
    CHECK(std::count_if(frame.begin(), frame.end(), [](const Return& r) { return r.object_id == 40; }) > 100);
}
