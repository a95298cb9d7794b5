// A scenario that extends another: the loaded result must equal the base with exactly the listed
// changes (positions worked out by hand from the numbers in the files), and every misuse is one
// InputError naming the file and the field.
#include <catch2/catch.hpp>

#include <fstream>

#include "ladarsim/core/input_error.h"
#include "ladarsim/scene/gltf_writer.h"
#include "ladarsim/scene/procedural_models.h"
#include "ladarsim/sensor_model/render/scenario.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;
using namespace ladarsim::sensor_model;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

void write(const fs::path& file, const std::string& text) {
    fs::create_directories(file.parent_path());
    std::ofstream(file) << text;
}

// Base: a plate model beside it, three objects; object 1 approaches at 10 m/s along -x.
void write_base(const fs::path& dir) {
    fs::create_directories(dir / "models");
    scene::write_gltf(scene::make_plate(1.0, 0.3), dir / "models" / "plate.glb");
    write(dir / "base.json", R"({
      "sensor": {"position_m": [0, 0, 3], "cue_object": 1},
      "render": {"frames": 7, "seed": 5},
      "objects": [
        {"id": 1, "class": "drone", "model": "models/plate.glb",
         "trajectory": {"type": "approach", "start_m": [1000, 0, 50], "towards_m": [0, 0, 50], "speed_mps": 10}},
        {"id": 2, "class": "bird", "model": "models/plate.glb",
         "trajectory": {"type": "fixed", "position_m": [500, 5, 40]}},
        {"id": 3, "class": "building", "model": "models/plate.glb",
         "trajectory": {"type": "fixed", "position_m": [200, 0, 0]}}
      ]
    })");
}

const scene::SceneObject& object(const Scenario& s, std::uint32_t id) {
    for (const auto& o : s.scene.objects)
        if (o.id == id) return o;
    FAIL("no object " << id);
    throw;
}

}  // namespace

TEST_CASE("a variant in another folder changes, removes and adds objects of the scenario it extends", "[scenario]") {
    const test::ScratchDir dir;
    write_base(dir / "a");
    write(dir / "b" / "variant.json", R"({
      "extends": "../a/base.json",
      "sensor": {"position_m": [0, 0, 60]},
      "objects": [
        {"id": 1, "trajectory": {"speed_mps": 20}},
        {"id": 3, "remove": true},
        {"id": 4, "class": "bird", "model": "../a/models/plate.glb",
         "trajectory": {"type": "fixed", "position_m": [300, 0, 30]}}
      ]
    })");
    const Scenario s = load_scenario(dir / "b" / "variant.json");
    CHECK(s.mount.position_world == Eigen::Vector3d(0, 0, 60));
    CHECK(s.mount.cue_object_id == 1);      // kept from the base's sensor object
    CHECK(s.render.frames == 7);            // a section the variant does not name is the base's
    REQUIRE(s.scene.objects.size() == 3);   // 1, 2, 4
    for (const auto& o : s.scene.objects) CHECK(o.id != 3);
    // Only the speed changed: 20 m/s for 2 s along -x from the base's start.
    CHECK((object(s, 1).trajectory.at(2.0).position - Eigen::Vector3d(960, 0, 50)).norm() < 1e-9);
    CHECK((object(s, 2).trajectory.at(0.0).position - Eigen::Vector3d(500, 5, 40)).norm() < 1e-12);
    CHECK((object(s, 4).trajectory.at(0.0).position - Eigen::Vector3d(300, 0, 30)).norm() < 1e-12);
    // The base's model path was read relative to the base, not to the variant.
    CHECK(object(s, 2).model->mesh.triangles.size() == 2);
    // The manifest records the merged scenario, with no trace of the mechanism.
    CHECK_FALSE(s.source.contains("extends"));
    CHECK(s.source["objects"][0]["trajectory"]["start_m"] == nlohmann::json::array({1000, 0, 50}));
}

TEST_CASE("a variant named without its folder, from the current directory, extends its base", "[scenario]") {
    // `ladarsim render variant.json` run in the variant's folder: its path has no parent.
    const test::ScratchDir dir;
    write_base(dir / "a");
    write(dir / "a" / "variant.json", R"({"extends": "base.json", "render": {"frames": 3}})");
    const fs::path before = fs::current_path();
    fs::current_path(dir / "a");
    Scenario s;
    CHECK_NOTHROW(s = load_scenario("variant.json"));
    fs::current_path(before);
    CHECK(s.render.frames == 3);
    CHECK(object(s, 2).model->mesh.triangles.size() == 2);  // the base's model, read beside the base
}

TEST_CASE("null deletes a key of the base and a chain of extensions applies in order", "[scenario]") {
    const test::ScratchDir dir;
    write_base(dir.path());
    write(dir / "mid.json", R"({"extends": "base.json", "sensor": {"cue_object": null}, "render": {"frames": 3}})");
    write(dir / "top.json", R"({"extends": "mid.json", "render": {"seed": 9}})");
    const Scenario s = load_scenario(dir / "top.json");
    CHECK(s.mount.cue_object_id == 0);
    CHECK(s.render.frames == 3);
    CHECK(s.render.seed == 9);
}

TEST_CASE("misused extends is one error naming the file and the field", "[scenario]") {
    const test::ScratchDir dir;
    write_base(dir.path());
    auto error_of = [&](const std::string& text) -> std::string {
        write(dir / "v.json", text);
        try {
            load_scenario(dir / "v.json");
        } catch (const InputError& e) {
            return e.what();
        }
        return "no error";
    };
    CHECK_THAT(error_of(R"({"extends": "none.json"})"), Contains("v.json: extends: no such file"));
    CHECK_THAT(error_of(R"({"extends": 3})"), Contains("v.json: extends: must be"));
    CHECK_THAT(error_of(R"({"extends": "v.json"})"), Contains("v.json: extends: extends itself"));
    CHECK_THAT(error_of(R"({"extends": "base.json", "objects": [{"id": 9, "remove": true}]})"),
               Contains("v.json: objects[0].remove:"));
    CHECK_THAT(error_of(R"({"extends": "base.json", "objects": [{"id": 2, "remove": false}]})"),
               Contains("v.json: objects[0].remove: must be true"));
    // A change the base's reader does not know is still a typo, named with its full path.
    CHECK_THAT(error_of(R"({"extends": "base.json", "objects": [{"id": 1, "trajectory": {"speed_mp": 20}}]})"),
               Contains("speed_mp"));
    // A cycle through two files.
    write(dir / "x.json", R"({"extends": "y.json"})");
    write(dir / "y.json", R"({"extends": "x.json"})");
    CHECK_THROWS_WITH(load_scenario(dir / "x.json"), Contains("extends itself"));
}

TEST_CASE("a scenario held in memory is read as a file of that folder would be, and named <scenario dict>", "[scenario]") {
    const test::ScratchDir dir;
    write_base(dir / "a");
    const nlohmann::json variant = nlohmann::json::parse(R"({
      "extends": "a/base.json",
      "objects": [{"id": 4, "class": "bird", "model": "a/models/plate.glb",
                   "trajectory": {"type": "fixed", "position_m": [300, 0, 30]}}]
    })");
    const Scenario s = load_scenario(variant, dir.path());
    CHECK(s.file == dir / "<scenario dict>");
    CHECK(s.render.frames == 7);
    REQUIRE(s.scene.objects.size() == 4);
    CHECK(object(s, 2).model->mesh.triangles.size() == 2);  // the base's path, relative to the base
    CHECK(object(s, 4).model->mesh.triangles.size() == 2);  // the document's own, relative to base_dir
    CHECK_FALSE(s.source.contains("extends"));

    auto error_of = [&](const std::string& text) -> std::string {
        try {
            load_scenario(nlohmann::json::parse(text), dir.path());
        } catch (const InputError& e) {
            return e.what();
        }
        return "no error";
    };
    CHECK(error_of(R"({"extends": "a/base.json", "render": {"frame": 3}})") ==
          (dir / "<scenario dict>").string() + ": render.frame: unknown key");
    CHECK_THAT(error_of(R"({"extends": "none.json"})"), Contains("<scenario dict>: extends: no such file"));
}
