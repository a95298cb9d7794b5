// A sensor on a moving platform (sensor.trajectory, sensor.sway): every pulse fires from the
// platform's pose at its own time, returns are reported in the sensor frame of that time, a cued
// gimbal is stabilised, and the dataset records the poses that bring the returns into the world.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

#include "ladarsim/core/units.h"
#include "ladarsim/dataset/frame_io.h"
#include "ladarsim/dataset/ground_truth_file.h"
#include "ladarsim/dataset/poses_file.h"
#include "ladarsim/sensor_model/render/frame_renderer.h"
#include "ladarsim/sensor_model/render/render_dataset.h"
#include "ladarsim/sensor_model/render/scenario.h"
#include "ladarsim/sensor_model/sensor/beam_geometry.h"
#include "../support/closed_form_scenario.h"
#include "../support/input_error_of.h"
#include "../support/scene_builders.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;
using namespace ladarsim::sensor_model;
using Catch::Matchers::Contains;

namespace {

constexpr double kWallX_m = 400.0;
constexpr double kSpeed_mps = 30.0;

/// The platform: 30 m/s along +x (nose along it), its heading swaying 2 deg at 1 Hz.
void ride_swaying_platform(SensorMount& mount) {
    mount.platform = scene::Trajectory::straight({0.0, 0.0, 0.0}, {kSpeed_mps, 0.0, 0.0});
    mount.sway = PlatformSway({{SwayComponent::Axis::yaw, 2.0 * kDeg, 1.0, 0.0}});
    mount.position_world = mount.platform->at(0.0).position;
}

/// A wall facing the sensor across x = kWallX_m, wide enough to fill the swaying field.
Scenario wall_scenario() {
    Scenario s = test::closed_form_scenario();
    s.scene.objects = {test::object_at(1, test::plate(60.0, 0.3), test::fixed_at(kWallX_m, 0.0, 0.0), scene::ObjectClass::building)};
    ride_swaying_platform(s.mount);
    return s;
}

/// Largest distance of a frame's returns from the wall plane, each placed with `pose_of(time)`.
template <class PoseOf>
double wall_residual_m(const std::vector<Return>& returns, PoseOf pose_of) {
    double worst = 0.0;
    for (const Return& r : returns) worst = std::max(worst, std::abs((pose_of(r.time_s) * r.position_sensor.cast<double>()).x() - kWallX_m));
    return worst;
}

}  // namespace

TEST_CASE("moving platform: every return, placed with the pose at its own time, lies on the wall within 1 cm", "[moving_platform]") {
    Scenario s = wall_scenario();
    FrameRenderer renderer(s);
    double worst_m = 0.0, worst_at_frame_start_m = 0.0;
    double heading_lo = 1.0, heading_hi = -1.0;
    // One second: a whole period of the sway.
    for (std::uint64_t k = 0; k < 20; ++k) {
        const Frame frame = renderer.render(k);
        REQUIRE(frame.returns.size() > 1000);
        worst_m = std::max(worst_m, wall_residual_m(frame.returns, [&](double t) { return s.mount.world_from_sensor(t); }));
        const Eigen::Isometry3d at_start = s.mount.world_from_sensor(frame.start_time_s);
        worst_at_frame_start_m = std::max(worst_at_frame_start_m, wall_residual_m(frame.returns, [&](double) { return at_start; }));
        const Eigen::Vector3d forward = at_start.linear().col(0);
        heading_lo = std::min(heading_lo, std::atan2(forward.y(), forward.x()));
        heading_hi = std::max(heading_hi, std::atan2(forward.y(), forward.x()));
        REQUIRE(frame.sensor_pose);
        CHECK(frame.sensor_pose->isApprox(at_start, 1e-15));
    }
    INFO("worst distance from the wall " << worst_m * 1000.0 << " mm; with each frame's start pose " << worst_at_frame_start_m * 1000.0
                                         << " mm; heading swung " << (heading_hi - heading_lo) / kDeg << " deg");
    CHECK(worst_m < 0.01);
    // The check has teeth: the platform moved and turned within each scan.
    CHECK(worst_at_frame_start_m > 0.1);
    CHECK((heading_hi - heading_lo) / kDeg > 3.0);
}

TEST_CASE("moving platform: the cued gimbal keeps a hovering drone in the field from the swaying platform", "[moving_platform]") {
    Scenario s = test::closed_form_scenario();
    ride_swaying_platform(s.mount);
    s.mount.gimbal_az_deg.reset();
    s.mount.gimbal_el_deg.reset();
    s.mount.cue_object_id = 1;
    // 300 m ahead and 100 m to the left: the platform's travel turns the line of sight too. A
    // backdrop three times as far along it returns every beam, so that each return tells where
    // the field's centre pointed at its time.
    const Eigen::Vector3d drone{300.0, 100.0, 20.0};
    s.scene.objects = {test::object_at(1, test::icosphere(0.3, 3, 0.3), scene::Trajectory::hover(drone, 0.0, 10.0)),
                       test::object_at(2, test::plate(150.0, 0.3), test::fixed_at(900.0, 300.0, 60.0), scene::ObjectClass::building)};
    FrameRenderer renderer(s);
    const ScanPattern& scan = renderer.raster();
    int seen = 0;
    double worst_az = 0.0, worst_el = 0.0, unstabilised_worst_az = 0.0;
    const int frames = 40;  // two periods of the sway
    for (std::uint64_t k = 0; k < static_cast<std::uint64_t>(frames); ++k) {
        const Frame frame = renderer.render(k);
        seen += std::any_of(frame.returns.begin(), frame.returns.end(), [](const Return& r) { return r.object_id == 1; });
        int backdrop = 0;
        for (const Return& r : frame.returns) {
            if (r.object_id != 2) continue;
            ++backdrop;
            // The field's centre at the return's time: its beam less the beam's place in the raster.
            const double centre_az = r.beam_az_rad - cell_centre_rad(r.column, scan.columns(), scan.field_az_rad());
            const double centre_el = r.beam_el_rad - cell_centre_rad(r.row, scan.rows(), scan.field_el_rad());
            const GimbalPointing to_drone = pointing_towards(s.mount.world_from_sensor(r.time_s).inverse() * drone);
            worst_az = std::max(worst_az, std::abs(to_drone.az_rad - centre_az));
            worst_el = std::max(worst_el, std::abs(to_drone.el_rad - centre_el));
            // A gimbal held still on the platform through the scan.
            unstabilised_worst_az = std::max(unstabilised_worst_az, std::abs(to_drone.az_rad - frame.gimbal_az_rad));
        }
        REQUIRE(backdrop > 2000);
    }
    INFO("drone seen in " << seen << " of " << frames << " frames; at most " << worst_az / kDeg << " deg (azimuth) and " << worst_el / kDeg
                          << " deg (elevation) off the field's centre; held on the platform " << unstabilised_worst_az / kDeg << " deg");
    CHECK(seen == frames);
    CHECK(worst_az < 0.25 * scan.field_az_rad());
    CHECK(worst_el < 0.25 * scan.field_el_rad());
    // Held still on the platform, the field (0.5 deg wide) would have lost it within a scan.
    CHECK(unstabilised_worst_az > 0.5 * scan.field_az_rad());
}

TEST_CASE("moving platform: poses.txt holds each frame's start pose and sensor_trajectory.txt places every return on the wall",
          "[moving_platform]") {
    const test::ScratchDir dir;
    Scenario s = wall_scenario();
    s.file = dir / "scenario.json";
    s.render.start_time_s = 0.3;
    DatasetOptions options;
    options.out_dir = dir / "d";
    options.frames = 4;
    render_dataset(s, options);
    const std::vector<Eigen::Isometry3d> poses = read_poses_txt(dir / "d" / "poses.txt");
    const std::vector<FrameGroundTruth> truth = read_ground_truth_json(dir / "d" / "ground_truth.json");
    const std::vector<TimedPose> trajectory = read_sensor_trajectory_txt(dir / "d" / "sensor_trajectory.txt");
    REQUIRE(poses.size() == 4);
    REQUIRE(truth.size() == 4);
    for (std::size_t k = 0; k < poses.size(); ++k) {
        const Eigen::Isometry3d expected = s.mount.world_from_sensor(0.3 + 0.05 * static_cast<double>(k));
        CHECK((poses[k].matrix() - expected.matrix()).cwiseAbs().maxCoeff() < 1e-12);
        REQUIRE(truth[k].sensor_pose);
        CHECK((truth[k].sensor_pose->matrix() - expected.matrix()).cwiseAbs().maxCoeff() < 1e-12);
        const std::vector<Return> frame = read_frame_pcd(dir / "d" / "frames" / (frame_file_stem(k) + ".pcd"));
        REQUIRE(frame.size() > 1000);
        // Only through the files, as a user compensates motion; the PCD's float coordinates carry
        // 0.03 mm at 400 m.
        CHECK(wall_residual_m(frame, [&](double t) { return pose_at(trajectory, t); }) < 0.01);
    }
}

TEST_CASE("moving platform: sensor.trajectory replaces position_m and takes an object's trajectory types", "[moving_platform]") {
    const test::ScratchDir dir;
    const nlohmann::json base = {{"sensor", {{"preset", "paper_ladar"}}}, {"objects", nlohmann::json::array()}};
    auto with_sensor = [&](const nlohmann::json& keys) {
        nlohmann::json d = base;
        d["sensor"].update(keys);
        return d;
    };
    nlohmann::json keyframes = {{"type", "keyframes"}};
    keyframes["keys"] = nlohmann::json::array({nlohmann::json{{"time_s", 0.0}, {"position_m", {0, 0, 10}}, {"yaw_deg", 0.0}},
                                               nlohmann::json{{"time_s", 10.0}, {"position_m", {100, 0, 10}}, {"yaw_deg", 30.0}}});
    const Scenario moving = load_scenario(with_sensor({{"trajectory", keyframes}, {"yaw_deg", 90.0}}), dir.path());
    REQUIRE(moving.mount.moves());
    // The mount's own yaw on top of the platform's: at 5 s the platform yaws 15 deg, the sensor 105.
    const Eigen::Vector3d forward = moving.mount.world_from_sensor(5.0).linear().col(0);
    CHECK(std::atan2(forward.y(), forward.x()) / kDeg == Approx(105.0).margin(1e-9));
    CHECK(moving.mount.world_from_sensor(5.0).translation().isApprox(Eigen::Vector3d(50.0, 0.0, 10.0)));

    // A platform that never moves is a fixed mount, exactly.
    const Scenario still = load_scenario(
        with_sensor({{"trajectory", {{"type", "fixed"}, {"position_m", {1, 2, 3}}, {"yaw_deg", 10.0}}}, {"yaw_deg", 5.0}}), dir.path());
    CHECK_FALSE(still.mount.moves());
    CHECK(still.mount.position_world == Eigen::Vector3d(1, 2, 3));

    const auto error_of = [&](const nlohmann::json& document) {
        return test::input_error_of([&] { load_scenario(document, dir.path()); });
    };
    CHECK(error_of(with_sensor({{"trajectory", keyframes}, {"position_m", {0, 0, 0}}})).field() == "sensor.position_m");
    CHECK(error_of(with_sensor({{"trajectory", {{"type", "straight"}, {"start_m", {0, 0, 0}}, {"velocity_mps", {1, 0, 0}}, {"speed", 3}}}}))
              .field() == "sensor.trajectory.speed");
    nlohmann::json sway = nlohmann::json::object();
    sway["components"] = nlohmann::json::array({nlohmann::json{{"axis", "roll"}, {"amplitude_deg", 3.0}, {"frequency_hz", 0.2}}});
    nlohmann::json in_metres = sway;
    in_metres["components"][0].erase("amplitude_deg");
    in_metres["components"][0]["amplitude_m"] = 3.0;
    CHECK(error_of(with_sensor({{"position_m", {0, 0, 0}}, {"sway", in_metres}})).field() == "sensor.sway.components[0].amplitude_deg");
    nlohmann::json misspelt = sway;
    misspelt["period"] = 1;
    CHECK(error_of(with_sensor({{"position_m", {0, 0, 0}}, {"sway", misspelt}})).field() == "sensor.sway.period");

    // A swaying mast: no trajectory, a sway. Its phase, not given, is drawn from the seed: the same
    // each time it is read, another with another seed.
    const auto roll_at = [&](const nlohmann::json& with_seed) {
        const Scenario mast = load_scenario(with_sensor({{"position_m", {0, 0, 30}}, {"sway", with_seed}}), dir.path());
        REQUIRE(mast.mount.moves());
        const Eigen::Vector3d up = mast.mount.world_from_sensor(1.0).linear().col(2);
        return std::atan2(-up.y(), up.z());
    };
    nlohmann::json seeded = sway;
    seeded["seed"] = 7;
    CHECK(roll_at(seeded) == roll_at(seeded));
    CHECK(roll_at(seeded) != roll_at(sway));
    CHECK(std::abs(roll_at(sway)) <= 3.0 * kDeg + 1e-12);
}
