// FrameRenderer end to end on hand-built scenes, against closed-form geometry and conservation.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "ladarsim/sensor_model/sensor/beam_geometry.h"
#include "ladarsim/sensor_model/render/frame_renderer.h"
#include "../support/closed_form_scenario.h"
#include "../support/scene_builders.h"

using namespace ladarsim;
using namespace ladarsim::sensor_model;
using namespace ladarsim::test;


TEST_CASE("a wall filling every footprint: one return per beam at the closed-form range", "[frame_renderer]") {
    Scenario s = closed_form_scenario();
    const double distance_m = 100.0, reflectance = 0.5;
    s.scene.objects.push_back(object_at(1, plate(50.0, reflectance), fixed_at(distance_m, 0, 0)));
    FrameRenderer renderer(s);
    const Frame f = renderer.render(0);

    REQUIRE(f.returns.size() == 150u * 20u);
    for (const auto& r : f.returns) {
        REQUIRE(r.return_index == 0);
        REQUIRE(r.object_id == 1);
        // Axis to a plane x = d: R = d / (cos el cos az). Averaging sub-ray ranges over the footprint
        // adds a second-order term of d * theta^2 / 2 < 1e-5 m for theta < 0.47 mrad.
        const double axis_range = distance_m / (std::cos(r.beam_el_rad) * std::cos(r.beam_az_rad));
        CHECK(r.range_m == Approx(axis_range).margin(1e-4));
        CHECK(r.position_sensor.x() == Approx(distance_m).margin(1e-3));
        // All the energy lands on one Lambertian surface at near-normal incidence: the extended-target
        // range equation (footprint averages of cos^3 differ from the axis value by < 1e-6).
        const double cos_axis = std::cos(r.beam_el_rad) * std::cos(r.beam_az_rad);
        CHECK(r.intensity == Approx(extended_target_photoelectrons(s.sensor, reflectance, cos_axis, axis_range)).epsilon(1e-5));
        CHECK(r.source == ReturnSource::surface);
    }
    // Raster order: rows top to bottom, columns left to right.
    CHECK(f.returns.front().beam_az_rad > f.returns[149].beam_az_rad);
    CHECK(f.returns.front().beam_el_rad > f.returns.back().beam_el_rad);
}

TEST_CASE("a wall bright enough to clip the detector: every return flagged and read at the clip level", "[frame_renderer][saturation]") {
    Scenario s = closed_form_scenario();
    const double distance_m = 100.0, reflectance = 0.5;
    s.scene.objects.push_back(object_at(1, plate(50.0, reflectance), fixed_at(distance_m, 0, 0)));
    // The wall's echo on the boresight, unclipped, and the photo-electrons a pulse of that shape
    // reads as when its peak current is I_sat: I_sat sigma sqrt(2 pi) / (gain q), sigma the
    // Gaussian pulse's (FWHM / (2 sqrt(2 ln 2))).
    const double full = extended_target_photoelectrons(s.sensor, reflectance, 1.0, distance_m);
    const double sigma_s = s.sensor.transmitter.pulse_width_ns * 1e-9 / (2.0 * std::sqrt(2.0 * std::log(2.0)));
    const double per_amp = sigma_s * std::sqrt(2.0 * M_PI) / (s.sensor.receiver.apd_gain * 1.602176634e-19);

    SECTION("clip at half the echo: every beam saturated, all at the clip level, counted in the ground truth") {
        s.sensor.receiver.saturation_current_a = 0.5 * full / per_amp;
        FrameRenderer renderer(s);
        const Frame f = renderer.render(0);
        REQUIRE(f.returns.size() == 150u * 20u);
        for (const auto& r : f.returns) {
            REQUIRE(r.saturated);
            CHECK(r.intensity == Approx(0.5 * full).epsilon(1e-5));
        }
        REQUIRE(f.ground_truth.size() == 1);
        CHECK(f.ground_truth[0].saturated_returns == f.ground_truth[0].returns);
    }
    SECTION("clip at twice the echo (the wall's edge beams see a little less): none saturated") {
        s.sensor.receiver.saturation_current_a = 2.0 * full / per_amp;
        FrameRenderer renderer(s);
        const Frame f = renderer.render(0);
        REQUIRE(f.returns.size() == 150u * 20u);
        for (const auto& r : f.returns) REQUIRE_FALSE(r.saturated);
        CHECK(f.ground_truth[0].saturated_returns == 0);
    }
}

TEST_CASE("a plate in front of a wall splits each footprint's energy between two returns", "[frame_renderer]") {
    Scenario s = closed_form_scenario();
    s.render.jitter = false;
    // The plate's edge at y = 0 runs through the field centre: beams near the centre see both.
    s.scene.objects.push_back(object_at(1, plate(50.0, 0.4), fixed_at(200.0, 0, 0)));
    s.scene.objects.push_back(object_at(2, plate(10.0, 0.8), fixed_at(150.0, -5.0, 0)));
    FrameRenderer renderer(s);
    const Frame f = renderer.render(0);

    int split_beams = 0;
    for (std::size_t i = 0; i < f.returns.size(); ++i) {
        const auto& r = f.returns[i];
        if (r.return_index != 1) continue;
        const auto& front = f.returns[i - 1];
        REQUIRE(front.object_id == 2);
        REQUIRE(r.object_id == 1);
        CHECK(front.range_m < r.range_m);
        // Energy conservation: the fractions of the footprint on the plate and on the wall, each
        // measured from its own pulse in the waveform, add up to the whole footprint (both surfaces
        // face the sensor within 0.3 deg, so cos = 1 to 2e-5).
        const double on_plate = front.intensity / extended_target_photoelectrons(s.sensor, 0.8, 1.0, front.range_m);
        const double on_wall = r.intensity / extended_target_photoelectrons(s.sensor, 0.4, 1.0, r.range_m);
        CHECK(on_plate + on_wall == Approx(1.0).epsilon(1e-3));
        ++split_beams;
    }
    CHECK(split_beams > 0);
}

TEST_CASE("ground at grazing incidence is one return per beam, however far its footprint stretches", "[frame_renderer]") {
    Scenario s = closed_form_scenario();
    const double height_m = 3.0, look_down_deg = 0.5;
    s.mount.position_world = {0.0, 0.0, height_m};
    s.mount.gimbal_el_deg = -look_down_deg;
    // A horizontal plate (pitch 90 deg turns its +x normal up) covering x = -500 .. 1500 m.
    s.scene.objects.push_back(object_at(
        1, plate(2000.0, 0.3), scene::Trajectory::fixed(scene::Pose{{500.0, 0.0, 0.0}, scene::orientation_from_ypr_deg(0, 90, 0)})));
    FrameRenderer renderer(s);
    const Frame f = renderer.render(0);

    // The footprint's 0.62 mrad spans about 25 m of range at 340 m; the sub-ray ranges differ by far
    // more than return_gap_m, yet they lie on one plane. The echo is weak and stretched: the far
    // beams (depression down to 0.25 deg, 690 m) fall below the threshold, but no beam splits.
    REQUIRE(f.returns.size() > 1000u);
    for (const auto& r : f.returns) {
        REQUIRE(r.return_index == 0);
        REQUIRE(std::isfinite(r.intensity));
        // The discriminator times the stretched pulse by its leading edge: metres before the axis
        // range h / sin(depression). Against the footprint integrated here, each sub-ray's range
        // h / sin(e) weighted by its irradiance and sin(e) / range^2 (incidence, spreading): 200 x
        // 200 cells, within 2e-6 of 800 x 800; the render is within 1e-4 (4 cm at 370 m).
        const double depression = -r.beam_el_rad;
        const double axis_range = height_m / std::sin(depression);
        const test::DiscriminatedEcho expected = test::discriminated_echo(s.sensor, s.render.footprint_truncation, [&](double, double y) {
            const double e = depression - y, range = height_m / std::sin(e);
            return std::pair{range, std::sin(e) / (range * range)};
        }, 200);
        CHECK(r.range_m < axis_range);
        CHECK(r.range_m == Approx(expected.range_m).epsilon(2e-4));
    }
}

TEST_CASE("a moving target is hit where its trajectory is at each beam's emission time", "[frame_renderer]") {
    Scenario s = closed_form_scenario();
    s.render.jitter = false;
    // A 0.5 m plate crossing the field from right to left at 200 m/s, 100 m away: during the
    // 20 ms frame it moves 4 m, so early and late lines see it in different columns.
    const double distance_m = 100.0, speed_mps = 200.0, side_m = 0.5;
    s.scene.objects.push_back(
        object_at(2, plate(side_m, 0.5), sliding({distance_m, -2.0, 0.0}, {0.0, speed_mps, 0.0})));
    s.render.motion_steps = 2;  // linear motion: Embree's interpolation between steps is exact
    FrameRenderer renderer(s);
    const Frame f = renderer.render(0);

    REQUIRE(!f.returns.empty());
    const double footprint_radius_m = distance_m * 0.5 * 0.62e-3 * s.render.footprint_truncation;
    for (const auto& r : f.returns) {
        REQUIRE(r.object_id == 2);
        // The beam axis crosses the plate's plane (x = 100 m; the plate faces along x) at y_axis;
        // the plate spanned y_centre +- side/2 at this beam's emission time.
        const double y_axis = distance_m * std::tan(r.beam_az_rad);
        const double y_centre = -2.0 + speed_mps * r.time_s;
        CHECK(std::abs(y_axis - y_centre) <= 0.5 * side_m + footprint_radius_m + 1e-6);
    }
    // Rows are 1 ms apart, so the plate's centre shifts 0.2 m per row: the mean azimuth of the
    // returns in the first and last lines that see it differs accordingly.
    const auto& first = f.returns.front();
    const auto& last = f.returns.back();
    CHECK(last.time_s > first.time_s);
    CHECK(last.beam_az_rad > first.beam_az_rad);
}

TEST_CASE("ground-truth boxes enclose the object's vertices at the frame's mid time", "[frame_renderer]") {
    Scenario s = closed_form_scenario();
    auto model = plate(0.3, 0.1);
    s.scene.objects.push_back(object_at(
        2, model, scene::Trajectory::keyframes({{0.0, {{80, 0, 0}, scene::orientation_from_ypr_deg(30, 10, 5)}},
                                                {1.0, {{60, 5, 3}, scene::orientation_from_ypr_deg(50, -10, 0)}}},
                                               scene::Interpolation::linear)));
    s.scene.objects.back().scale = 2.0;
    FrameRenderer renderer(s);
    const Frame f = renderer.render(3);
    REQUIRE(f.ground_truth.size() == 1);
    const auto& g = f.ground_truth[0];
    CHECK(g.time_s == Approx(0.5 * (f.start_time_s + f.end_time_s)));
    const Eigen::Isometry3d world_from_object = s.scene.objects[0].trajectory.at(g.time_s).world_from_object();
    for (const auto& p : model->mesh.positions) {
        const Eigen::Vector3d world = world_from_object * (2.0 * p.cast<double>());
        const Eigen::Vector3d in_box = g.box_world.orientation.conjugate() * (world - g.box_world.centre);
        for (int a = 0; a < 3; ++a) CHECK(std::abs(in_box[a]) <= 0.5 * g.box_world.size[a] + 1e-9);
    }
    // The sensor-frame box is the same box seen from the sensor (mount at the origin, level).
    CHECK((g.box_sensor.centre - g.box_world.centre).norm() < 1e-9);
}

TEST_CASE("frames are identical with one, two and eight threads", "[frame_renderer]") {
    Scenario s = closed_form_scenario();
    // Every random process on: speckle, noise, jitter, false alarms, waveforms at the plate's edges,
    // stratified footprints over a map.
    s.render.noise = true;
    s.sensor.receiver.range_folding = true;
    s.sensor.receiver.false_alarm_rate_hz = 1e5;  // about one false alarm per frame
    s.scene.objects.push_back(object_at(1, plate(50.0, 0.3), fixed_at(300.0, 0, 0)));
    s.scene.objects.push_back(
        object_at(2, plate(0.3, 0.6), sliding({250.0, -1.0, 0.2}, {0.0, 40.0, 0.0})));
    // A patch of recorded map between them (tilted discs: its footprints take stratified sub-rays).
    scene::BackgroundMap map;
    for (int i = 0; i < 200; ++i) {
        const double y = -0.8 + 0.1 * (i % 20), z = -0.5 + 0.1 * (i / 20);
        map.points_world.emplace_back(270.0 + 0.3 * std::sin(7.0 * i), y, z);
        map.normals.push_back(Eigen::Vector3f(-1.0f, 0.3f * float(std::sin(3.0 * i)), 0.3f * float(std::cos(5.0 * i))).normalized());
        map.radii_m.push_back(0.07f);
        map.reflectance.push_back(0.2f + 0.1f * float(i % 3));
    }
    s.scene.background = std::move(map);
    auto render_with = [&](int threads) {
        // An arena of its own, and permission for more threads than cores: eight workers even on
        // a two-core machine.
        tbb::global_control allow(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
        tbb::task_arena arena(threads);
        return arena.execute([&] {
            FrameRenderer renderer(s);
            return renderer.render(1);
        });
    };
    const Frame one = render_with(1);
    REQUIRE(std::any_of(one.returns.begin(), one.returns.end(), [](const Return& r) { return r.object_id == scene::kBackgroundObjectId; }));
    for (int threads : {2, 8}) {
        const Frame other = render_with(threads);
        INFO(threads << " threads");
        REQUIRE(one.returns.size() == other.returns.size());
        for (std::size_t i = 0; i < one.returns.size(); ++i) {
            const auto& a = one.returns[i];
            const auto& b = other.returns[i];
            REQUIRE(std::memcmp(&a.range_m, &b.range_m, sizeof a.range_m) == 0);
            REQUIRE(std::memcmp(&a.intensity, &b.intensity, sizeof a.intensity) == 0);
            REQUIRE(std::memcmp(&a.snr, &b.snr, sizeof a.snr) == 0);
            REQUIRE(a.object_id == b.object_id);
            REQUIRE(a.column == b.column);
            REQUIRE(a.row == b.row);
        }
    }
}

TEST_CASE("a cued gimbal slews towards the target at its rate limit", "[frame_renderer]") {
    Scenario s = closed_form_scenario();
    s.mount.gimbal_az_deg = 0.0;
    s.mount.gimbal_el_deg = 0.0;
    s.mount.cue_object_id = 2;
    // Target 45 deg to the left: 16 deg/s at 20 Hz is 0.8 deg per frame.
    s.scene.objects.push_back(object_at(2, plate(0.3, 0.5), fixed_at(100.0, 100.0, 0.0)));
    FrameRenderer renderer(s);
    const double deg = std::numbers::pi / 180.0;
    CHECK(renderer.gimbal_pointing(0).az_rad == Approx(0.0));
    CHECK(renderer.gimbal_pointing(10).az_rad == Approx(8.0 * deg));
    CHECK(renderer.gimbal_pointing(100).az_rad == Approx(45.0 * deg));
    CHECK(renderer.gimbal_pointing(100).el_rad == Approx(0.0).margin(1e-12));
}

namespace {

/// How far a return lies from an object's ground-truth box, beyond the footprint: the return sits
/// on the beam axis at its range, and the part of the footprint that met the object can be up to
/// the footprint's truncation radius off that axis.
double beyond_footprint(const Scenario& s, const GroundTruthObject& g, const Return& r) {
    const Eigen::Vector3d local = g.box_sensor.orientation.conjugate() * (r.position_sensor.cast<double>() - g.box_sensor.centre);
    const double outside = (local.cwiseAbs() - 0.5 * g.box_sensor.size).cwiseMax(0.0).norm();
    const double footprint_m = r.range_m * s.render.footprint_truncation * 0.5 * s.sensor.transmitter.divergence_mrad * 1e-3;
    return std::max(0.0, outside - footprint_m);
}

/// Largest distance of the returns labelled `object_id` from that object's box, beyond the footprint.
double worst_outside(const Scenario& s, const Frame& f, std::uint32_t object_id, int& labelled) {
    double worst = 0.0;
    for (const GroundTruthObject& g : f.ground_truth) {
        if (g.object_id != object_id) continue;
        for (const Return& r : f.returns) {
            if (r.object_id != object_id) continue;
            ++labelled;
            worst = std::max(worst, beyond_footprint(s, g, r));
        }
    }
    return worst;
}

}  // namespace

TEST_CASE("a tower's returns lie on the tower, not on the ground merged in front of it", "[frame_renderer][labels]") {
    // A 30 x 30 x 80 m tower 1 km out on flat ground, seen from 60 m up at its foot: the footprints
    // there hold the tower's face and metres of grazing ground in front of it, in one continuous run
    // of range. A return labelled tower must have its range set by the tower (docs/sensor.md).
    Scenario s = closed_form_scenario();
    set_raster(s.sensor, 32, 20, 0.5 * 32 / 150, 0.5);
    s.mount.position_world = {0.0, 0.0, 60.0};
    s.mount.gimbal_el_deg = -std::atan2(60.0, 1000.0) * 180.0 / M_PI;
    s.scene.objects.push_back(object_at(1, plate(4000.0, 0.3), scene::Trajectory::fixed(scene::Pose{
                                                                   {1000.0, 0.0, 0.0}, scene::orientation_from_ypr_deg(0, 90, 0)}),
                                        scene::ObjectClass::terrain));
    s.scene.objects.push_back(object_at(2, std::make_shared<scene::Model>(scene::make_box_building(30.0, 30.0, 80.0)),
                                        fixed_at(1015.0, 0.0, 0.0), scene::ObjectClass::building));
    FrameRenderer renderer(s);
    const Frame f = renderer.render(0);
    int labelled = 0;
    const double worst = worst_outside(s, f, 2, labelled);
    REQUIRE(labelled > 100);
    // Half the pulse length: the reach of a range measured on the tower's own echo.
    CHECK(worst < 0.15);
}

TEST_CASE("a bird inside a cloud: its returns lie on the bird, the cloud's on the cloud", "[frame_renderer][labels]") {
    // A 0.4 m bird at the centre of a 40 m cloud (20 /km, 1 /km/sr) 640 m out: the cloud's broad
    // backscatter starts metres before the bird, and a peak on top of it is timed from the cloud's
    // leading edge when the cloud sets the 50 % crossing.
    Scenario s = closed_form_scenario();
    set_raster(s.sensor, 32, 4, 0.5 * 32 / 150, 0.5 * 4 / 20);
    s.scene.objects.push_back(object_at(40, std::make_shared<scene::Model>(scene::make_cloud(40.0, 0.02)), fixed_at(640.0, 0.0, 0.0),
                                        scene::ObjectClass::cloud));
    s.scene.objects.push_back(object_at(32, std::make_shared<scene::Model>(scene::make_bird(0.4)), fixed_at(645.0, 0.0, 0.0),
                                        scene::ObjectClass::bird));
    FrameRenderer renderer(s);
    int labelled = 0;
    double worst = 0.0;
    for (std::uint64_t frame = 0; frame < 4; ++frame) worst = std::max(worst, worst_outside(s, renderer.render(frame), 32, labelled));
    // The bird is seen (where its echo stands clear of the cloud's), and never named for a
    // range the cloud set.
    REQUIRE(labelled >= 4);
    CHECK(worst < 0.15);
}
