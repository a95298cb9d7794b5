// glTF node animation: samplers against their closed forms, through write_gltf and load_gltf, and
// the scenario key that picks or stops a model's animations.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <memory>

#include "ladarsim/core/input_error.h"
#include "ladarsim/scene/animation.h"
#include "ladarsim/scene/gltf_loader.h"
#include "ladarsim/scene/gltf_writer.h"
#include "ladarsim/scene/procedural_models.h"
#include "ladarsim/scene/scene_file.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;
using namespace ladarsim::scene;

namespace {

constexpr double kDeg = M_PI / 180.0;

// A plate whose one node sits at `pivot` and carries both triangles, with one clip of the given channels.
Model animated_plate(const Eigen::Vector3d& pivot, std::vector<AnimationChannel> channels) {
    Model m = make_plate(1.0, 0.5);
    auto animation = std::make_shared<Animation>();
    AnimationNode node;
    node.name = "plate";
    node.translation = pivot;
    animation->nodes.push_back(node);
    animation->parts.push_back({0, 0, static_cast<std::uint32_t>(m.mesh.triangles.size())});
    AnimationClip clip{"turn", std::move(channels), 0.0};
    for (const auto& c : clip.channels) clip.duration_s = std::max(clip.duration_s, c.times_s.back());
    animation->clips.push_back(std::move(clip));
    m.animation = animation;
    return m;
}

AnimationChannel yaw_channel(AnimationInterpolation interpolation, std::vector<double> times, std::vector<double> yaw_deg) {
    AnimationChannel c;
    c.path = AnimationPath::rotation;
    c.interpolation = interpolation;
    c.times_s = times;
    for (double a : yaw_deg) {
        const Eigen::Quaterniond q(Eigen::AngleAxisd(a * kDeg, Eigen::Vector3d::UnitZ()));
        c.values.insert(c.values.end(), {q.x(), q.y(), q.z(), q.w()});
    }
    return c;
}

// The yaw of the plate's normal (+x at rest) after `motion`.
double yaw_deg(const Eigen::Affine3d& motion) {
    const Eigen::Vector3d n = motion.linear() * Eigen::Vector3d::UnitX();
    return std::atan2(n.y(), n.x()) / kDeg;
}

Eigen::Affine3d motion_at(const Model& m, double t, AnimationChoice choice = {}) {
    std::vector<Eigen::Affine3d> out;
    part_motions(m, choice, t, out);
    REQUIRE(out.size() == 1);
    return out[0];
}

}  // namespace

TEST_CASE("linear rotation keys slerp at a steady rate and loop with the clip", "[animation]") {
    // 0, 90, 180 deg at 0, 1, 2 s: 90 deg/s throughout, the 180 deg key reached the long way
    // round is no shorter path, so the keys are 90 deg apart.
    const Model m = animated_plate({0, 0, 0}, {yaw_channel(AnimationInterpolation::linear, {0, 1, 2}, {0, 90, 180})});
    for (double t : {0.0, 0.25, 0.6, 1.0, 1.3}) CHECK(yaw_deg(motion_at(m, t)) == Approx(90.0 * t).margin(1e-9));
    // Past the 2 s loop it starts again.
    CHECK(yaw_deg(motion_at(m, 2.5)) == Approx(45.0).margin(1e-9));
    CHECK(yaw_deg(motion_at(m, -0.5)) == Approx(135.0).margin(1e-9));
}

TEST_CASE("step keys hold, cubic-spline keys follow the Hermite curve, translation and scale channels move the part", "[animation]") {
    SECTION("step") {
        const Model m = animated_plate({0, 0, 0}, {yaw_channel(AnimationInterpolation::step, {0, 1, 2}, {10, 40, 10})});
        CHECK(yaw_deg(motion_at(m, 0.99)) == Approx(10.0).margin(1e-9));
        CHECK(yaw_deg(motion_at(m, 1.01)) == Approx(40.0).margin(1e-9));
    }
    SECTION("cubic spline translation with zero tangents: smoothstep between the keys") {
        AnimationChannel c;
        c.path = AnimationPath::translation;
        c.interpolation = AnimationInterpolation::cubic_spline;
        c.times_s = {0.0, 2.0};
        // in-tangent, value, out-tangent per key
        c.values = {0, 0, 0, 0, 0, 0, 0, 0, 0, /**/ 0, 0, 0, 4, 0, 0, 0, 0, 0};
        c.node = 0;
        const Model m = animated_plate({0, 0, 0}, {c});
        const double s = 0.25;  // t = 0.5 s
        CHECK(motion_at(m, 0.5).translation().x() == Approx(4.0 * (3 * s * s - 2 * s * s * s)).margin(1e-12));
    }
    SECTION("cubic spline with tangents: the derivative at a key is its tangent") {
        AnimationChannel c;
        c.path = AnimationPath::translation;
        c.interpolation = AnimationInterpolation::cubic_spline;
        c.times_s = {0.0, 1.0};
        c.values = {0, 0, 0, 0, 0, 0, 3, 0, 0, /**/ 3, 0, 0, 3, 0, 0, 0, 0, 0};  // a straight line at 3 m/s
        const Model m = animated_plate({0, 0, 0}, {c});
        CHECK(motion_at(m, 0.3).translation().x() == Approx(0.9).margin(1e-12));
    }
    SECTION("linear scale about the node") {
        AnimationChannel c;
        c.path = AnimationPath::scale;
        c.interpolation = AnimationInterpolation::linear;
        c.times_s = {0.0, 1.0};
        c.values = {1, 1, 1, 3, 3, 3};
        const Eigen::Vector3d pivot(5, 0, 0);
        const Model m = animated_plate(pivot, {c});
        const Eigen::Affine3d motion = motion_at(m, 0.5);
        // The node's origin stays; a point 1 m from it is now 2 m from it.
        CHECK((motion * pivot - pivot).norm() < 1e-12);
        CHECK((motion * (pivot + Eigen::Vector3d::UnitY()) - pivot).norm() == Approx(2.0).margin(1e-12));
    }
}

TEST_CASE("a rotation turns the part about its node's origin, and animations can be stopped", "[animation]") {
    const Eigen::Vector3d pivot(0, 2, 0);
    const Model m = animated_plate(pivot, {yaw_channel(AnimationInterpolation::linear, {0, 1, 2}, {0, 90, 180})});
    const Eigen::Affine3d motion = motion_at(m, 1.0);
    CHECK((motion * pivot - pivot).norm() < 1e-12);
    CHECK((motion * Eigen::Vector3d(1, 2, 0) - Eigen::Vector3d(0, 3, 0)).norm() < 1e-12);
    AnimationChoice none;
    none.mode = AnimationChoice::Mode::none;
    CHECK_FALSE(animates(m, none));
    CHECK(animates(m, AnimationChoice{}));
    CHECK(yaw_deg(motion_at(m, 1.0, none)) == Approx(0.0).margin(1e-12));
    // The box over the animation holds the plate turned to 90 deg (it spans x then).
    const Eigen::AlignedBox3d box = animated_bounds(m, AnimationChoice{});
    CHECK(box.min().x() <= -0.5);
    CHECK(box.max().x() >= 0.5);
    CHECK(animated_bounds(m, none).sizes().x() == Approx(0.0).margin(1e-9));
}

TEST_CASE("write_gltf and load_gltf keep a model's animation: nodes, parts and every kind of sampler", "[animation][gltf]") {
    test::ScratchDir dir;
    AnimationChannel move;
    move.path = AnimationPath::translation;
    move.interpolation = AnimationInterpolation::cubic_spline;
    move.times_s = {0.0, 2.0};
    move.values = {0, 0, 0, 1, 2, 3, 0.5, 0, 0, /**/ 0, 0.5, 0, 2, 2, 3, 0, 0, 0};
    const Model m = animated_plate({1, 2, 3}, {yaw_channel(AnimationInterpolation::linear, {0, 1, 2}, {0, 90, 180}),
                                               yaw_channel(AnimationInterpolation::step, {0, 0.5}, {0, 10}), move});
    for (const char* name : {"a.glb", "a.gltf"}) {
        write_gltf(m, dir / name);
        const Model back = load_gltf(dir / name);
        REQUIRE(back.animation);
        REQUIRE(back.animation->clips.size() == 1);
        CHECK(back.animation->clips[0].name == "turn");
        CHECK(back.animation->clips[0].duration_s == Approx(2.0));
        REQUIRE(back.animation->parts.size() == 1);
        CHECK(back.animation->parts[0].triangle_count == 2u);
        CHECK(back.bounds().isApprox(m.bounds(), 1e-6f));
        for (double t : {0.0, 0.3, 0.7, 1.2, 1.9, 2.4}) {
            const Eigen::Affine3d a = motion_at(m, t), b = motion_at(back, t);
            CHECK((a.matrix() - b.matrix()).norm() < 1e-5);
        }
    }
}

TEST_CASE("the bundled bird beats its wings and the quadcopter turns its rotors, also after make-assets", "[animation][procedural]") {
    test::ScratchDir dir;
    write_default_assets(dir.path());
    for (const Model& bird : {make_bird(0.4), load_gltf(dir / "bird.glb")}) {
        REQUIRE(animates(bird, {}));
        REQUIRE(bird.animation->parts.size() == 2);
        // The left wing's tip (y = 0.2 m) at the top and the bottom of the beat.
        std::vector<Eigen::Affine3d> up, down;
        part_motions(bird, {}, 0.25 / kBirdWingbeatHz, up);
        part_motions(bird, {}, 0.75 / kBirdWingbeatHz, down);
        const Eigen::Vector3d hinge(0, 0.016, 0.008), tip(0, 0.2, 0.008);
        const double up_deg = std::atan2((up[1] * tip - hinge).z(), (up[1] * tip - hinge).y()) / kDeg;
        const double down_deg = std::atan2((down[1] * tip - hinge).z(), (down[1] * tip - hinge).y()) / kDeg;
        CHECK(up_deg == Approx(kWingMeanDeg + kWingAmplitudeDeg).margin(0.5));
        CHECK(down_deg == Approx(kWingMeanDeg - kWingAmplitudeDeg).margin(0.5));
        CHECK(bird.animation->clips[0].duration_s == Approx(1.0 / kBirdWingbeatHz).epsilon(1e-6));
    }
    for (const Model& quad : {make_quadcopter(), load_gltf(dir / "quadcopter.glb")}) {
        REQUIRE(animates(quad, {}));
        REQUIRE(quad.animation->parts.size() == 4);
        std::vector<Eigen::Affine3d> motion;
        // A quarter of a revolution later each rotor has turned 90 deg, neighbours in opposite senses.
        part_motions(quad, {}, 0.25 / kRotorRevolutionsPerSecond, motion);
        for (std::size_t k = 0; k < 4; ++k) {
            const Eigen::Vector3d x = motion[k].linear() * Eigen::Vector3d::UnitX();
            CHECK(x.y() == Approx(k % 2 == 0 ? 1.0 : -1.0).margin(1e-5));
        }
    }
}

TEST_CASE("a scenario object's animation key plays all, one or none of the model's animations, and names the choices when wrong", "[animation][scene_file]") {
    test::ScratchDir dir;
    write_gltf(animated_plate({0, 0, 0}, {yaw_channel(AnimationInterpolation::linear, {0, 1}, {0, 90})}), dir / "plate.glb");
    const auto read = [&](const std::string& animation_key) {
        nlohmann::json j = {{"objects", {{{"id", 1}, {"class", "drone"}, {"model", "plate.glb"},
                                          {"trajectory", {{"type", "fixed"}, {"position_m", {10, 0, 0}}}}}}}};
        if (!animation_key.empty()) j["objects"][0]["animation"] = animation_key;
        JsonFields f(j, (dir / "s.json").string(), "");
        Scene s = read_scene(f, dir.path());
        return s.objects.at(0).animation;
    };
    CHECK(read("").mode == AnimationChoice::Mode::all);
    CHECK(read("all").mode == AnimationChoice::Mode::all);
    CHECK(read("none").mode == AnimationChoice::Mode::none);
    const AnimationChoice one = read("turn");
    CHECK(one.mode == AnimationChoice::Mode::one);
    CHECK(one.clip == 0u);
    try {
        read("spin");
        FAIL("an unknown animation name was accepted");
    } catch (const InputError& e) {
        const std::string what = e.what();
        CHECK(what.find("objects[0].animation") != std::string::npos);
        CHECK(what.find("\"turn\"") != std::string::npos);
    }
}
