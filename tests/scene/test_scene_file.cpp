// read_scene: the objects and background of a scenario file. Trajectory positions are checked
// against hand computation from the numbers in the scenario; every error must name its field.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "ladarsim/core/input_error.h"
#include "ladarsim/core/json_fields.h"
#include "ladarsim/scene/scene_file.h"

using namespace ladarsim::scene;
using ladarsim::InputError;
using ladarsim::JsonFields;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

std::string base64(const std::vector<std::uint8_t>& bytes) {
    static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::uint32_t b0 = bytes[i];
        const std::uint32_t b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0;
        const std::uint32_t b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0;
        const std::uint32_t triple = (b0 << 16) | (b1 << 8) | b2;
        out += kAlphabet[(triple >> 18) & 63];
        out += kAlphabet[(triple >> 12) & 63];
        out += i + 1 < bytes.size() ? kAlphabet[(triple >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? kAlphabet[triple & 63] : '=';
    }
    return out;
}

template <typename T>
void append(std::vector<std::uint8_t>& bytes, const std::vector<T>& values) {
    const std::size_t at = bytes.size();
    bytes.resize(at + values.size() * sizeof(T));
    std::memcpy(bytes.data() + at, values.data(), values.size() * sizeof(T));
}

/// A 2 x 1 x 0.5 box (glTF units) as glTF text with an embedded buffer: ten triangles of
/// material "body" (reflectance 0.2), the two top (+y in glTF) triangles of material "rotor" (0.4).
std::string box_gltf() {
    const std::vector<float> positions{0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0,
                                       0, 0, 0.5f, 2, 0, 0.5f, 2, 1, 0.5f, 0, 1, 0.5f};
    const std::vector<std::uint32_t> body{0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                          1, 2, 6, 1, 6, 5, 0, 4, 7, 0, 7, 3};
    const std::vector<std::uint32_t> rotor{3, 7, 6, 3, 6, 2};
    std::vector<std::uint8_t> buffer;
    append(buffer, positions);
    append(buffer, body);
    append(buffer, rotor);
    nlohmann::json g = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"meshes",
         {{{"primitives",
            {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"material", 0}, {"mode", 4}},
             {{"attributes", {{"POSITION", 0}}}, {"indices", 2}, {"material", 1}, {"mode", 4}}}}}}},
        {"materials",
         {{{"name", "body"}, {"extras", {{"ladar", {{"reflectance", 0.2}}}}}},
          {{"name", "rotor"}, {"extras", {{"ladar", {{"reflectance", 0.4}}}}}}}},
        {"buffers",
         {{{"byteLength", buffer.size()}, {"uri", "data:application/octet-stream;base64," + base64(buffer)}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 96}, {"target", 34962}},
          {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 120}, {"target", 34963}},
          {{"buffer", 0}, {"byteOffset", 216}, {"byteLength", 24}, {"target", 34963}}}},
        {"accessors",
         {{{"bufferView", 0}, {"componentType", 5126}, {"count", 8}, {"type", "VEC3"},
           {"min", {0, 0, 0}}, {"max", {2, 1, 0.5}}},
          {{"bufferView", 1}, {"componentType", 5125}, {"count", 30}, {"type", "SCALAR"}},
          {{"bufferView", 2}, {"componentType", 5125}, {"count", 6}, {"type", "SCALAR"}}}}};
    return g.dump(1);
}

/// dir/scenarios (where scenario files "live") and dir/models/box.gltf, removed at the end.
struct ScenarioDir {
    fs::path root, scenarios;
    ScenarioDir() {
        std::random_device rd;
        root = fs::temp_directory_path() / ("ladarsim-test-scene-file-" + std::to_string(rd()));
        scenarios = root / "scenarios";
        fs::create_directories(scenarios);
        fs::create_directories(root / "models");
        std::ofstream(root / "models" / "box.gltf") << box_gltf();
    }
    ~ScenarioDir() { fs::remove_all(root); }

    Scene read(const std::string& json_text) const {
        const nlohmann::json j = nlohmann::json::parse(json_text);
        JsonFields top(j, "scenario.json", "");
        Scene scene = read_scene(top, scenarios);
        top.reject_unknown_keys();  // read_scene must have used "objects" and "background"
        return scene;
    }

    /// The error read() throws for `json_text`; fails the test if there is none.
    InputError error(const std::string& json_text) const {
        try {
            read(json_text);
        } catch (const InputError& e) {
            return e;
        }
        FAIL("no InputError for " << json_text);
        throw;  // unreachable: FAIL throws
    }
};

/// One object using the box, with the given trajectory and extra object fields.
std::string one_object(const std::string& trajectory, const std::string& extra = "") {
    return R"({"objects": [{"id": 1, "class": "drone", "model": "../models/box.gltf", )" + extra +
           R"("trajectory": )" + trajectory + "}]}";
}

void check_near(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected) {
    INFO("actual " << actual.transpose() << ", expected " << expected.transpose());
    CHECK((actual - expected).norm() < 1e-9);
}

}  // namespace

TEST_CASE("scene_file: every trajectory type, positions by hand", "[scene_file]") {
    ScenarioDir dir;
    const Scene scene = dir.read(R"({"objects": [
      {"id": 1, "class": "building", "model": "../models/box.gltf",
       "trajectory": {"type": "fixed", "position_m": [1, 2, 3], "yaw_deg": 90, "pitch_deg": 30}},
      {"id": 2, "class": "drone", "model": "../models/box.gltf",
       "trajectory": {"type": "straight", "start_m": [1000, 0, 20], "velocity_mps": [-15, 0, 0]}},
      {"id": 3, "class": "drone", "model": "../models/box.gltf",
       "trajectory": {"type": "approach", "start_m": [120, 1, 4], "towards_m": [0, 0, 4], "speed_mps": 15}},
      {"id": 4, "class": "bird", "model": "../models/box.gltf",
       "trajectory": {"type": "winding", "start_m": [0, 0, 10], "velocity_mps": [10, 0, 0],
                      "amplitude_m": 2, "period_s": 4}},
      {"id": 5, "class": "drone", "model": "../models/box.gltf",
       "trajectory": {"type": "hover", "centre_m": [5, 5, 30], "radius_m": 1, "period_s": 8}},
      {"id": 6, "class": "plane", "model": "../models/box.gltf",
       "trajectory": {"type": "keyframes", "keys": [
          {"time_s": 0, "position_m": [0, 0, 0]},
          {"time_s": 2, "position_m": [10, 0, 0], "yaw_deg": 90},
          {"time_s": 4, "position_m": [10, 10, 0]}]}},
      {"id": 7, "class": "drone", "model": "../models/box.gltf",
       "trajectory": {"type": "keyframes", "interpolation": "smooth", "keys": [
          {"time_s": 0, "position_m": [0, 0, 0]},
          {"time_s": 2, "position_m": [10, 0, 0]},
          {"time_s": 4, "position_m": [10, 10, 0]}]}},
      {"id": 8, "class": "drone", "model": "../models/box.gltf",
       "trajectory": {"type": "hover", "centre_m": [-3, 2, 40]}}
    ]})");
    REQUIRE(scene.objects.size() == 8);
    CHECK_FALSE(scene.background.has_value());
    const auto at = [&](std::size_t i, double t) { return scene.objects[i].trajectory.at(t).position; };

    // fixed: yaw 90 turns forward (+x) to +y, then 30 deg nose up lifts it: (0, cos 30, sin 30).
    const Pose fixed = scene.objects[0].trajectory.at(123.0);
    check_near(fixed.position, {1, 2, 3});
    check_near(fixed.orientation * Eigen::Vector3d::UnitX(), {0, std::cos(std::numbers::pi / 6), 0.5});
    CHECK(scene.objects[0].trajectory.is_static());
    CHECK(scene.objects[0].object_class == ObjectClass::building);

    // straight: start + v t.
    check_near(at(1, 2.0), {970, 0, 20});

    // approach: start + speed t (towards - start) / |towards - start|, |(-120, -1, 0)| = sqrt(14401).
    const double d = std::sqrt(14401.0);
    check_near(at(2, 3.0), {120 - 45 * 120 / d, 1 - 45 * 1 / d, 4});
    check_near(at(2, 0.0), {120, 1, 4});

    // winding: start + v t + A sin(2 pi t / T) * (left of v = +y).
    check_near(at(3, 1.0), {10, 2, 10});
    check_near(at(3, 3.0), {30, -2, 10});
    CHECK(scene.objects[3].object_class == ObjectClass::bird);

    // hover: centre + r (cos, sin)(2 pi t / T): a quarter period is +y.
    check_near(at(4, 2.0), {5, 6, 30});

    // keyframes, linear: halfway along each leg; clamped after the last key.
    check_near(at(5, 1.0), {5, 0, 0});
    check_near(at(5, 3.0), {10, 5, 0});
    check_near(at(5, 10.0), {10, 10, 0});
    check_near(scene.objects[5].trajectory.at(2.0).orientation * Eigen::Vector3d::UnitX(), {0, 1, 0});

    // keyframes, smooth: through the keys, and off the straight legs between them.
    check_near(at(6, 2.0), {10, 0, 0});
    check_near(at(6, 4.0), {10, 10, 0});
    CHECK((at(6, 1.0) - Eigen::Vector3d(5, 0, 0)).norm() > 1e-3);

    // hover without radius: holds its position.
    check_near(at(7, 3.7), {-3, 2, 40});
    CHECK(scene.objects[7].trajectory.is_static());

    // Defaults: name from class and id, scale 1.
    CHECK(scene.objects[1].name == "drone-2");
    CHECK(scene.objects[1].scale == 1.0);
}

TEST_CASE("scene_file: yaw, pitch and roll of a fixed object", "[scene_file]") {
    ScenarioDir dir;
    const Scene scene = dir.read(one_object(
        R"({"type": "fixed", "position_m": [0, 0, 0], "yaw_deg": 90, "pitch_deg": 30, "roll_deg": 90})"));
    const Eigen::Quaterniond q = scene.objects[0].trajectory.at(0).orientation;
    // Roll 90 about the body's forward axis lifts the left wing (+y) to the body's up, which the
    // 30 deg nose-up pitch tips back to (-sin 30, 0, cos 30) and the 90 deg yaw turns to (0, -sin 30, cos 30).
    check_near(q * Eigen::Vector3d::UnitY(), {0, -0.5, std::cos(std::numbers::pi / 6)});
    check_near(q * Eigen::Vector3d::UnitX(), {0, std::cos(std::numbers::pi / 6), 0.5});
}

TEST_CASE("scene_file: models are loaded once and shared, and overrides get a private copy", "[scene_file]") {
    ScenarioDir dir;
    const Scene scene = dir.read(R"({"objects": [
      {"id": 1, "class": "drone", "model": "../models/box.gltf", "size_m": 0.3,
       "trajectory": {"type": "fixed", "position_m": [0, 0, 0]}},
      {"id": 2, "class": "drone", "model": "../models/./box.gltf", "scale": 2.5,
       "trajectory": {"type": "fixed", "position_m": [5, 0, 0]}},
      {"id": 3, "class": "drone", "model": "../models/box.gltf", "reflectance": 0.05,
       "materials": {"rotor": {"reflectance": 0.7}},
       "trajectory": {"type": "fixed", "position_m": [9, 0, 0]}},
      {"id": 4, "class": "drone", "model": "../models/box.gltf", "materials": {"body": {"reflectance": 0.9}},
       "trajectory": {"type": "fixed", "position_m": [9, 0, 0]}}
    ]})");
    REQUIRE(scene.objects.size() == 4);
    const auto& shared = scene.objects[0].model;
    CHECK(scene.objects[1].model.get() == shared.get());
    CHECK(scene.objects[2].model.get() != shared.get());
    CHECK(scene.objects[3].model.get() != shared.get());

    const auto reflectance_of = [](const Model& m, const std::string& name) {
        for (const auto& mat : m.materials) {
            if (mat.name == name) return mat.reflectance;
        }
        FAIL("no material " << name);
        return -1.0;
    };
    // The shared model keeps the file's values.
    CHECK(reflectance_of(*shared, "body") == Approx(0.2));
    CHECK(reflectance_of(*shared, "rotor") == Approx(0.4));
    // Object-wide reflectance first, then the named material on top.
    CHECK(reflectance_of(*scene.objects[2].model, "body") == Approx(0.05));
    CHECK(reflectance_of(*scene.objects[2].model, "rotor") == Approx(0.7));
    CHECK(reflectance_of(*scene.objects[3].model, "body") == Approx(0.9));
    CHECK(reflectance_of(*scene.objects[3].model, "rotor") == Approx(0.4));

    // size_m: the box's largest extent is 2 model units, so 0.3 m needs scale 0.15.
    CHECK(scene.objects[0].scale == Approx(0.15));
    CHECK(scene.objects[1].scale == 2.5);
}

TEST_CASE("scene_file: unknown keys are rejected at every level with their full path", "[scene_file]") {
    ScenarioDir dir;
    CHECK(dir.error(one_object(R"({"type": "straight", "start_m": [0, 0, 0], "velocity_mps": [1, 0, 0]})",
                               R"("colour": "red", )"))
              .field() == "objects[0].colour");
    CHECK(dir.error(one_object(R"({"type": "approach", "start_m": [0, 0, 0], "towards_m": [1, 0, 0],
                                   "speed_mps": 3, "sped_mps": 3})"))
              .field() == "objects[0].trajectory.sped_mps");
    CHECK(dir.error(one_object(R"({"type": "keyframes", "keys": [{"time_s": 0, "position_m": [0, 0, 0]},
                                   {"time_s": 1, "position_m": [1, 0, 0], "yaw": 3}]})"))
              .field() == "objects[0].trajectory.keys[1].yaw");
    CHECK(dir.error(one_object(R"({"type": "fixed", "position_m": [0, 0, 0]})",
                               R"("materials": {"rotor": {"reflectance": 0.5, "reflectivity": 0.5}}, )"))
              .field() == "objects[0].materials.rotor.reflectivity");
    // A key that belongs to another trajectory type is unknown here.
    CHECK(dir.error(one_object(R"({"type": "fixed", "position_m": [0, 0, 0], "velocity_mps": [1, 0, 0]})"))
              .field() == "objects[0].trajectory.velocity_mps");

    std::ofstream(dir.scenarios / "map.pcd") << "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                                                "COUNT 1 1 1\nWIDTH 5\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 5\n"
                                                "DATA ascii\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n2 1 0\n";
    const InputError e = dir.error(R"({"background": {"file": "map.pcd", "offset": [0, 0, 0]}})");
    CHECK(e.field() == "background.offset");
    CHECK(e.file() == "scenario.json");
    CHECK_THAT(std::string(e.what()), Contains("scenario.json: background.offset: unknown key"));
}

TEST_CASE("scene_file: bad values name their field", "[scene_file]") {
    ScenarioDir dir;
    const std::string fixed = R"({"type": "fixed", "position_m": [0, 0, 0]})";
    const auto field_and_problem = [&](const std::string& json_text, const std::string& field,
                                       const std::string& problem_part) {
        const InputError e = dir.error(json_text);
        CHECK(e.field() == field);
        CHECK_THAT(e.problem(), Contains(problem_part));
    };

    SECTION("wrong types") {
        field_and_problem(R"({"objects": [{"id": "1", "class": "drone", "model": "../models/box.gltf",
                              "trajectory": {"type": "fixed", "position_m": [0, 0, 0]}}]})",
                          "objects[0].id", "whole number");
        field_and_problem(one_object(R"({"type": "straight", "start_m": "here", "velocity_mps": [1, 0, 0]})"),
                          "objects[0].trajectory.start_m", "3 numbers");
        field_and_problem(one_object(R"("fixed")"), "objects[0].trajectory", "expected an object");
        field_and_problem(R"({"objects": {"id": 1}})", "objects", "expected an array");
        field_and_problem(R"({"objects": [7]})", "objects[0]", "expected an object");
        field_and_problem(one_object(fixed, R"("reflectance": "dark", )"), "objects[0].reflectance", "number");
    }
    SECTION("out of range") {
        field_and_problem(one_object(R"({"type": "winding", "start_m": [0, 0, 0], "velocity_mps": [1, 0, 0],
                                         "amplitude_m": 1, "period_s": -2})"),
                          "objects[0].trajectory.period_s", "outside");
        field_and_problem(one_object(R"({"type": "hover", "centre_m": [0, 0, 0], "period_s": 0})"),
                          "objects[0].trajectory.period_s", "greater than 0");
        field_and_problem(one_object(R"({"type": "approach", "start_m": [0, 0, 0], "towards_m": [5, 0, 0],
                                         "speed_mps": 0})"),
                          "objects[0].trajectory.speed_mps", "greater than 0");
        field_and_problem(one_object(fixed, R"("reflectance": 1.5, )"), "objects[0].reflectance", "outside");
        field_and_problem(one_object(fixed, R"("size_m": -0.3, )"), "objects[0].size_m", "outside");
        field_and_problem(R"({"objects": [{"id": 0, "class": "drone", "model": "../models/box.gltf",
                              "trajectory": {"type": "fixed", "position_m": [0, 0, 0]}}]})",
                          "objects[0].id", "outside [1, ");
        field_and_problem(one_object(R"({"type": "fixed", "position_m": [0, 0, 0], "pitch_deg": 95})"),
                          "objects[0].trajectory.pitch_deg", "outside");
    }
    SECTION("inconsistent or missing") {
        field_and_problem(one_object(fixed, R"("size_m": 0.3, "scale": 2, )"), "objects[0].scale", "not both");
        field_and_problem(one_object(R"({"type": "approach", "start_m": [1, 2, 3], "towards_m": [1, 2, 3],
                                         "speed_mps": 5})"),
                          "objects[0].trajectory.towards_m", "equals start_m");
        field_and_problem(one_object(R"({"position_m": [0, 0, 0]})"), "objects[0].trajectory.type", "missing");
        field_and_problem(one_object(R"({"type": "circle"})"), "objects[0].trajectory.type", "fixed, straight");
        field_and_problem(R"({"objects": [{"id": 1, "class": "drone", "model": "../models/box.gltf"}]})",
                          "objects[0].trajectory", "missing");
        field_and_problem(one_object(R"({"type": "keyframes", "keys": []})"), "objects[0].trajectory.keys",
                          "at least one");
        field_and_problem(one_object(R"({"type": "keyframes", "keys": [{"time_s": 0, "position_m": [0, 0, 0]},
                                         {"time_s": 2, "position_m": [1, 0, 0]},
                                         {"time_s": 2, "position_m": [2, 0, 0]}]})"),
                          "objects[0].trajectory.keys[2].time_s", "later than");
        field_and_problem(one_object(R"({"type": "keyframes", "interpolation": "cubic",
                                         "keys": [{"time_s": 0, "position_m": [0, 0, 0]}]})"),
                          "objects[0].trajectory.interpolation", "linear, smooth");
    }
    SECTION("duplicate ids name the later object and the first") {
        const InputError e = dir.error(R"({"objects": [
          {"id": 4, "class": "drone", "model": "../models/box.gltf", "trajectory": {"type": "fixed", "position_m": [0, 0, 0]}},
          {"id": 5, "class": "drone", "model": "../models/box.gltf", "trajectory": {"type": "fixed", "position_m": [0, 0, 0]}},
          {"id": 4, "class": "drone", "model": "../models/box.gltf", "trajectory": {"type": "fixed", "position_m": [0, 0, 0]}}
        ]})");
        CHECK(e.field() == "objects[2].id");
        CHECK_THAT(e.problem(), Contains("objects[0]"));
    }
    SECTION("classes") {
        const std::string all = "drone, bird, plane, building, terrain, tree, cloud";
        field_and_problem(R"({"objects": [{"id": 1, "class": "ufo", "model": "../models/box.gltf",
                              "trajectory": {"type": "fixed", "position_m": [0, 0, 0]}}]})",
                          "objects[0].class", all);
        // The background class belongs to the recorded map alone.
        field_and_problem(R"({"objects": [{"id": 1, "class": "background", "model": "../models/box.gltf",
                              "trajectory": {"type": "fixed", "position_m": [0, 0, 0]}}]})",
                          "objects[0].class", all);
        field_and_problem(R"({"objects": [{"id": 1, "model": "../models/box.gltf",
                              "trajectory": {"type": "fixed", "position_m": [0, 0, 0]}}]})",
                          "objects[0].class", "missing");
    }
    SECTION("files") {
        const InputError e = dir.error(R"({"objects": [{"id": 1, "class": "drone", "model": "../models/nothing.glb",
                                           "trajectory": {"type": "fixed", "position_m": [0, 0, 0]}}]})");
        CHECK(e.field() == "objects[0].model");
        CHECK_THAT(e.problem(), Contains("nothing.glb"));
        field_and_problem(one_object(fixed, R"("materials": {"propeller": {"reflectance": 0.5}}, )"),
                          "objects[0].materials.propeller", "\"body\", \"rotor\"");
        field_and_problem(R"({"background": {"file": "no_map.pcd"}})", "background.file", "no_map.pcd");
        field_and_problem(R"({"background": {"offset_m": [0, 0, 0]}})", "background.file", "missing");
    }
}

TEST_CASE("scene_file: the background map is placed and coloured as the scenario says", "[scene_file]") {
    ScenarioDir dir;
    // Five points on z = 0 with intensities 0..200; the scenario offsets them and fixes reflectance.
    std::ofstream(dir.scenarios / "map.pcd")
        << "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\n"
           "WIDTH 6\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 6\nDATA ascii\n"
           "0 0 0 0\n1 0 0 40\n0 1 0 80\n1 1 0 120\n2 1 0 160\n2 0 0 200\n";
    const Scene fixed_rho = dir.read(R"({"background": {"file": "map.pcd", "offset_m": [100, -50, 2.5],
                                         "reflectance": 0.25, "neighbours": 5}})");
    REQUIRE(fixed_rho.background.has_value());
    const BackgroundMap& map = *fixed_rho.background;
    REQUIRE(map.points_world.size() == 6);
    check_near(map.points_world[0], {100, -50, 2.5});
    check_near(map.points_world[4], {102, -49, 2.5});
    for (float r : map.reflectance) CHECK(r == Approx(0.25));
    for (const auto& n : map.normals) CHECK((n - Eigen::Vector3f::UnitZ()).norm() < 1e-5f);

    const Scene from_intensity =
        dir.read(R"({"background": {"file": "map.pcd", "reflectance_at_max_intensity": 0.5}})");
    CHECK(from_intensity.background->reflectance[2] == Approx(0.5 * 80.0 / 200.0));

    const InputError both =
        dir.error(R"({"background": {"file": "map.pcd", "reflectance": 0.2, "reflectance_at_max_intensity": 0.5}})");
    CHECK(both.field() == "background.reflectance_at_max_intensity");
    const Scene calibrated = dir.read(R"({"background": {"file": "map.pcd", "reflectance_per_intensity": 0.004}})");
    CHECK(calibrated.background->reflectance[2] == Approx(0.004 * 80.0));
    CHECK(dir.error(R"({"background": {"file": "map.pcd", "reflectance_per_intensity": 0.01, "reflectance": 0.2}})").field() ==
          "background.reflectance_per_intensity");
    const Scene scanned = dir.read(R"({"background": {"file": "map.pcd", "scanner_position_m": [0.5, 0.5, 10]}})");
    for (const auto& n : scanned.background->normals) CHECK((n - Eigen::Vector3f::UnitZ()).norm() < 1e-5f);
    CHECK(dir.error(R"({"background": {"file": "map.pcd", "scanner_position_m": [0, 0]}})").field() ==
          "background.scanner_position_m");
    CHECK(dir.error(R"({"background": {"file": "map.pcd", "neighbours": 2}})").field() == "background.neighbours");
}
