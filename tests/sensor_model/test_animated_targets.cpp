// Targets animated by glTF node channels, rendered: each pulse sees the moving part where it is
// at that pulse's time, and a beating wing shows in the return count from frame to frame.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <vector>

#include <Eigen/Eigenvalues>

#include "ladarsim/scene/animation.h"
#include "ladarsim/scene/gltf_loader.h"
#include "ladarsim/scene/gltf_writer.h"
#include "ladarsim/scene/procedural_models.h"
#include "ladarsim/sensor_model/render/frame_renderer.h"
#include "../support/closed_form_scenario.h"
#include "../support/scene_builders.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;
using namespace ladarsim::sensor_model;
using namespace ladarsim::test;

namespace {

constexpr double kDeg = M_PI / 180.0;

// The turning plate with keys a second apart, 90 deg apart, from `start_deg`, through a glTF file.
std::shared_ptr<const scene::Model> turning_plate_file(const std::filesystem::path& file, double side_m, double start_deg) {
    std::vector<std::pair<double, double>> keys;
    for (int k = 0; k <= 4; ++k) keys.emplace_back(k, start_deg + 90.0 * k);
    scene::write_gltf(turning_plate(side_m, keys), file);
    return std::make_shared<scene::Model>(scene::load_gltf(file));
}

}  // namespace

TEST_CASE("a plate turning 90 deg/s by a glTF rotation channel shows in each frame's returns the angle it has at those beams' times", "[frame_renderer][animation]") {
    ScratchDir dir;
    const double side_m = 0.6, distance_m = 100.0, start_deg = -40.0, rate_dps = 90.0;
    Scenario s = closed_form_scenario();
    s.render.jitter = false;
    s.scene.objects.push_back(object_at(1, turning_plate_file(dir / "plate.glb", side_m, start_deg), fixed_at(distance_m, 0, 0)));
    FrameRenderer renderer(s);
    const auto yaw_at = [&](double t) { return start_deg + rate_dps * t; };
    double worst_angle_deg = 0.0, worst_offset_m = 0.0;
    // 20 ms frames over 0.9 s: the plate turns from -40 to +41 deg, 1.8 deg within each frame.
    for (int frame = 0; frame < 18; frame += 2) {
        const Frame f = renderer.render(frame);
        std::vector<Eigen::Vector3d> points;
        double yaw_sum = 0.0;
        for (const auto& r : f.returns) {
            if (r.object_id != 1) continue;
            // Beams whose footprint lies wholly on the plate at their own time: 5 cm in from its edges.
            const double yaw = yaw_at(r.time_s) * kDeg;
            const Eigen::Vector3d p = r.position_sensor.cast<double>() - Eigen::Vector3d(distance_m, 0, 0);
            const Eigen::Vector3d in_plate = Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()) * p;
            if (std::abs(in_plate.y()) > 0.5 * side_m - 0.05 || std::abs(in_plate.z()) > 0.5 * side_m - 0.05) continue;
            worst_offset_m = std::max(worst_offset_m, std::abs(in_plate.x()));
            points.push_back(r.position_sensor.cast<double>());
            yaw_sum += yaw_at(r.time_s);
        }
        REQUIRE(points.size() > 100u);
        Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
        for (const auto& p : points) centroid += p;
        centroid /= static_cast<double>(points.size());
        Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
        for (const auto& p : points) scatter += (p - centroid) * (p - centroid).transpose();
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter);
        Eigen::Vector3d n = eigen.eigenvectors().col(0);  // the least-spread direction: the plane's normal
        if (n.x() < 0.0) n = -n;
        const double fitted_deg = std::atan2(n.y(), n.x()) / kDeg;
        const double expected_deg = yaw_sum / static_cast<double>(points.size());
        INFO("frame " << frame << ": fitted " << fitted_deg << " deg, the beams' times say " << expected_deg << " deg");
        CHECK(std::abs(fitted_deg - expected_deg) < 1.0);
        worst_angle_deg = std::max(worst_angle_deg, std::abs(fitted_deg - expected_deg));
    }
    // Each of those returns lies on the plate where it was at that return's own time: the plate
    // turns 1.8 deg in a frame, which at 0.25 m from its axis is 8 mm.
    INFO("largest angle error " << worst_angle_deg << " deg, largest distance off the plate at its time " << worst_offset_m << " m");
    CHECK(worst_offset_m < 0.002);
    WARN("turning plate: largest fitted-angle error " << worst_angle_deg << " deg; largest return offset from the plate at its time "
                                                      << worst_offset_m << " m");
}

TEST_CASE("the bundled bird seen side on at 150 m: its return count per frame peaks in the spectrum at the wingbeat frequency", "[frame_renderer][animation]") {
    Scenario s = closed_form_scenario();
    s.render.jitter = false;
    const auto bird = std::make_shared<scene::Model>(scene::load_gltf(std::filesystem::path(LADARSIM_SOURCE_DIR) / "assets/models/bird.glb"));
    // Nose along +y, across the line of sight: the wings point at the sensor and away, and its
    // side faces it. A fixed place keeps it inside the 0.5 deg field for the whole run.
    scene::Pose pose;
    pose.position = {150.0, 0.0, 0.0};
    pose.orientation = scene::orientation_from_ypr_deg(90.0, 0.0, 0.0);
    s.scene.objects.push_back(object_at(1, bird, scene::Trajectory::fixed(pose)));
    FrameRenderer renderer(s);
    const int frames = 256;
    std::vector<double> counts;
    for (int frame = 0; frame < frames; ++frame) {
        const Frame f = renderer.render(frame);
        counts.push_back(static_cast<double>(std::count_if(f.returns.begin(), f.returns.end(), [](const auto& r) { return r.object_id == 1; })));
    }
    const double frame_rate_hz = 1.0 / (renderer.render(1).start_time_s - renderer.render(0).start_time_s);
    double mean = 0.0;
    for (double c : counts) mean += c / frames;
    // Periodogram of the count, bins 1 .. N/2.
    std::vector<double> power;
    for (int k = 1; k <= frames / 2; ++k) {
        std::complex<double> sum = 0.0;
        for (int n = 0; n < frames; ++n) sum += (counts[static_cast<std::size_t>(n)] - mean) * std::polar(1.0, -2.0 * M_PI * k * n / frames);
        power.push_back(std::norm(sum));
    }
    const auto peak = std::max_element(power.begin(), power.end());
    const double peak_hz = static_cast<double>(peak - power.begin() + 1) * frame_rate_hz / frames;
    std::vector<double> sorted = power;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    const double median = sorted[sorted.size() / 2];
    INFO("mean count " << mean << ", peak " << peak_hz << " Hz, peak / median power " << *peak / median);
    REQUIRE(*peak > 0.0);
    CHECK(std::abs(peak_hz - scene::kBirdWingbeatHz) <= 0.1 * scene::kBirdWingbeatHz);
    CHECK(*peak >= 10.0 * median);
    WARN("bird at 150 m: mean " << mean << " returns a frame, spectral peak at " << peak_hz << " Hz (wingbeat "
                                << scene::kBirdWingbeatHz << " Hz), " << *peak / median << " x the median power");
}
