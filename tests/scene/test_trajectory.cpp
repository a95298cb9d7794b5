// Trajectories against their closed forms: positions, headings, clamping, the sensor's angle conventions.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "ladarsim/scene/trajectory.h"

using namespace ladarsim::scene;
using Eigen::Vector3d;

namespace {
constexpr double kPi = std::numbers::pi;
Vector3d nose(const Pose& p) { return p.orientation * Vector3d::UnitX(); }
}  // namespace

TEST_CASE("aircraft angles: yaw turns x to y, pitch lifts the nose, roll turns y to z", "[trajectory]") {
    CHECK((orientation_from_ypr_deg(90, 0, 0) * Vector3d::UnitX()).isApprox(Vector3d::UnitY(), 1e-12));
    CHECK((orientation_from_ypr_deg(0, 30, 0) * Vector3d::UnitX()).isApprox(Vector3d(std::cos(kPi / 6), 0, 0.5), 1e-12));
    CHECK((orientation_from_ypr_deg(0, 0, 90) * Vector3d::UnitY()).isApprox(Vector3d::UnitZ(), 1e-12));
    // Intrinsic order: after yawing 90 deg, pitching up still lifts the (now northward) nose.
    CHECK((orientation_from_ypr_deg(90, 30, 0) * Vector3d::UnitX()).isApprox(Vector3d(0, std::cos(kPi / 6), 0.5), 1e-12));
}

TEST_CASE("straight: constant velocity, nose along it", "[trajectory]") {
    const Vector3d start(600, 30, 25), v(-14, -0.7, -0.25);
    const Trajectory t = Trajectory::straight(start, v);
    CHECK_FALSE(t.is_static());
    for (double time : {0.0, 1.5, 37.25}) {
        const Pose p = t.at(time);
        CHECK((p.position - (start + time * v)).norm() < 1e-9);
        CHECK(nose(p).isApprox(v.normalized(), 1e-12));
    }
    // A climbing object pitches its nose up.
    CHECK(nose(Trajectory::straight(start, {3, 0, 4}).at(0)).isApprox(Vector3d(0.6, 0, 0.8), 1e-12));
    CHECK(Trajectory::straight(start, Vector3d::Zero()).is_static());
}

TEST_CASE("keyframes: linear between keys, slerp orientation, clamped outside", "[trajectory]") {
    const Pose a{{0, 0, 10}, orientation_from_ypr_deg(0, 0, 0)};
    const Pose b{{100, 50, 10}, orientation_from_ypr_deg(90, 0, 0)};
    const Trajectory t = Trajectory::keyframes({{2.0, a}, {6.0, b}}, Interpolation::linear);
    CHECK((t.at(3.0).position - Vector3d(25, 12.5, 10)).norm() < 1e-12);
    CHECK(nose(t.at(4.0)).isApprox(Vector3d(std::sqrt(0.5), std::sqrt(0.5), 0), 1e-12));  // half way: 45 deg
    CHECK(t.at(-1.0).position == a.position);
    CHECK(t.at(60.0).position == b.position);
    CHECK_THROWS(Trajectory::keyframes({{1.0, a}, {1.0, b}}, Interpolation::linear));
    CHECK_THROWS(Trajectory::keyframes({}, Interpolation::linear));
}

TEST_CASE("smooth keyframes pass through every key and are exact on evenly spaced collinear keys", "[trajectory]") {
    std::vector<Keyframe> keys;
    for (int i = 0; i < 5; ++i) keys.push_back({1.0 * i, {Vector3d(10.0 * i, 0.0, 3.0), Eigen::Quaterniond::Identity()}});
    keys[2].pose.position.y() = 7.0;  // a bend in the middle
    const Trajectory t = Trajectory::keyframes(keys, Interpolation::smooth);
    for (const auto& k : keys) CHECK((t.at(k.time_s).position - k.pose.position).norm() < 1e-12);
    // Catmull-Rom reproduces straight uniform motion exactly between inner keys.
    std::vector<Keyframe> line;
    for (int i = 0; i < 4; ++i) line.push_back({2.0 * i, {Vector3d(5.0 * i, -i, 0), Eigen::Quaterniond::Identity()}});
    const Trajectory s = Trajectory::keyframes(line, Interpolation::smooth);
    CHECK((s.at(3.3).position - Vector3d(5.0 * 1.65, -1.65, 0)).norm() < 1e-12);
}

TEST_CASE("winding: a sinusoid of the given amplitude about the straight path, horizontal and perpendicular", "[trajectory]") {
    const Vector3d start(0, 0, 50), v(10, 0, 0);
    const double amplitude = 4.0, period = 8.0;
    const Trajectory t = Trajectory::winding(start, v, amplitude, period);
    CHECK((t.at(2.0).position - (start + 2.0 * v + Vector3d(0, amplitude, 0))).norm() < 1e-12);  // quarter period
    CHECK((t.at(4.0).position - (start + 4.0 * v)).norm() < 1e-9);
    CHECK((t.at(6.0).position - (start + 6.0 * v - Vector3d(0, amplitude, 0))).norm() < 1e-9);
    // At a zero crossing the heading turns by atan(A omega / |v|) towards the weave.
    const double slope = amplitude * 2.0 * kPi / period / 10.0;
    CHECK(nose(t.at(0.0)).isApprox(Vector3d(1, slope, 0).normalized(), 1e-12));
    CHECK_THROWS(Trajectory::winding(start, v, amplitude, 0.0));
}

TEST_CASE("hover: a circle of the given radius about the centre", "[trajectory]") {
    const Vector3d centre(300, -20, 40);
    const Trajectory t = Trajectory::hover(centre, 2.5, 30.0);
    for (double time : {0.0, 7.5, 11.0, 29.0}) {
        const Vector3d d = t.at(time).position - centre;
        CHECK(d.norm() == Approx(2.5).epsilon(1e-12));
        CHECK(d.z() == 0.0);
    }
    CHECK((t.at(7.5).position - (centre + Vector3d(0, 2.5, 0))).norm() < 1e-12);
    CHECK(Trajectory::hover(centre, 0.0, 30.0).is_static());
}
