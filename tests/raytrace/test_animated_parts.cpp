// An animated part traced where its animation puts it at each ray's own time, against the closed
// form of a plate turning about its vertical axis while it slides.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "ladarsim/raytrace/traced_scene.h"
#include "ladarsim/scene/animation.h"
#include "ladarsim/scene/procedural_models.h"
#include "../support/rays.h"
#include "../support/scene_builders.h"

using namespace ladarsim;
using namespace ladarsim::test;
using raytrace::Ray;
using raytrace::TracedScene;

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kKeyInterval_s = 1.0 / 120.0;

// The yaw of key k: steps of 90 and 30 deg in turn, so the rate changes at every key (a
// steady turn would be exact for any slerp between samples, and test nothing).
double key_yaw_deg(int k) { return 120.0 * (k / 2) + (k % 2 == 1 ? 90.0 : 0.0); }

// The yaw the LINEAR rotation channel gives at time t: between keys under 180 deg apart about one
// axis, a slerp turns at a steady rate.
double yaw_deg_at(double t) {
    const int k = static_cast<int>(std::floor(t / kKeyInterval_s));
    const double f = t / kKeyInterval_s - k;
    return key_yaw_deg(k) + f * (key_yaw_deg(k + 1) - key_yaw_deg(k));
}

// A square plate facing +-x at rest, turned about the vertical through its centre by 240 deg
// every 1/60 s (1.9 turns in a 20 ms frame, as fast as the quadcopter's rotors).
std::shared_ptr<const scene::Model> turning_plate(double side_m, int keys) {
    scene::Model m = scene::make_plate(side_m, 0.5);
    auto animation = std::make_shared<scene::Animation>();
    animation->nodes.push_back(scene::AnimationNode{});
    animation->parts.push_back({0, 0, static_cast<std::uint32_t>(m.mesh.triangles.size())});
    scene::AnimationChannel turn;
    turn.path = scene::AnimationPath::rotation;
    turn.interpolation = scene::AnimationInterpolation::linear;
    for (int k = 0; k < keys; ++k) {
        const Eigen::Quaterniond q(Eigen::AngleAxisd(key_yaw_deg(k) * kDeg, Eigen::Vector3d::UnitZ()));
        turn.times_s.push_back(k * kKeyInterval_s);
        turn.values.insert(turn.values.end(), {q.x(), q.y(), q.z(), q.w()});
    }
    animation->clips.push_back(scene::AnimationClip{"turn", {turn}, (keys - 1) * kKeyInterval_s});
    m.animation = animation;
    return std::make_shared<scene::Model>(std::move(m));
}

}  // namespace

TEST_CASE("an animated part is hit exactly where its animation and trajectory put it at each ray's time", "[traced_scene][animation]") {
    const double side_m = 0.6, half = 0.5 * side_m;
    const Eigen::Vector3d start(120.0, -0.4, 0.1), velocity(0.0, 30.0, 0.0);
    scene::Scene scene;
    scene.objects.push_back(object_at(3, turning_plate(side_m, 64), sliding(start, velocity)));
    const Eigen::Vector3d sensor = Eigen::Vector3d::Zero();
    TracedScene traced(scene, sensor);
    const double begin = 0.1, end = 0.12;
    traced.set_time_window(begin, end, 2);

    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> when(begin, end), across(-0.5, 0.5);
    int hits_checked = 0, misses_checked = 0;
    double worst_m = 0.0;
    for (int i = 0; i < 2000; ++i) {
        const double t = when(random);
        const Eigen::Vector3d centre = start + t * velocity;
        const Ray r = ray_from(sensor, centre + Eigen::Vector3d(0.0, across(random), across(random)), t);
        const double yaw = yaw_deg_at(t) * kDeg;
        const Eigen::Vector3d normal(std::cos(yaw), std::sin(yaw), 0.0), along(-std::sin(yaw), std::cos(yaw), 0.0);
        const double range = plane_distance(r, centre, normal);
        const Eigen::Vector3d p = r.origin_world + range * r.direction;
        // Where the ray crosses the plate's plane, in the plate's own coordinates.
        const double w = std::abs((p - centre).dot(along)), h = std::abs(p.z() - centre.z());
        const auto hit = traced.trace(r);
        if (w < half - 1e-4 && h < half - 1e-4) {
            INFO("t " << t << " s, yaw " << yaw / kDeg << " deg");
            REQUIRE(hit);
            CHECK(hit->object_id == 3u);
            worst_m = std::max(worst_m, std::abs(hit->range_m - range));
            CHECK(std::abs(std::abs(hit->normal_world.cast<double>().dot(normal)) - 1.0) < 1e-6);
            ++hits_checked;
        } else if (w > half + 1e-4 || h > half + 1e-4) {
            CHECK_FALSE(hit);
            ++misses_checked;
        }
    }
    INFO("largest range error " << worst_m << " m");
    CHECK(worst_m < 1e-6);
    CHECK(hits_checked > 200);
    CHECK(misses_checked > 200);
}
