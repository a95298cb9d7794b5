// The shipped scenarios: each loads, renders, keeps its drone in the field, and shows the clutter
// it promises; the initial map holds no target.
#include <catch2/catch.hpp>

#include <cmath>
#include <set>

#include "ladarsim/dataset/frame_pcd.h"
#include "ladarsim/sensor_model/render/frame_renderer.h"
#include "ladarsim/sensor_model/render/render_dataset.h"
#include "../support/scratch_dir.h"
#include "../support/shared_data.h"
#include "../support/skip.h"

using namespace ladarsim;
using namespace ladarsim::sensor_model;

namespace {
const std::filesystem::path kScenarios = std::filesystem::path(LADARSIM_SOURCE_DIR) / "assets/scenarios";
}

namespace {

struct Seen {
    int target = 0, clutter = 0, map = 0;
    std::size_t clutter_objects = 0;  ///< objects that count as clutter in the scenario
};

/// Renders `frames` of a scenario and counts the returns of the target (id 1), of its clutter
/// (moving objects other than drones, clouds, and buildings that are not the modelled ground's)
/// and of the recorded map; checks that the cue keeps the drone's box inside the field and that
/// every return has a finite, positive range.
Seen render_and_check(const Scenario& s, std::initializer_list<std::uint64_t> frames) {
    FrameRenderer renderer(s);
    std::set<std::uint32_t> clutter;
    for (const auto& o : s.scene.objects) {
        const bool flyer = !o.trajectory.is_static() && o.object_class != scene::ObjectClass::drone;
        const bool obstacle = o.object_class == scene::ObjectClass::cloud || (o.object_class == scene::ObjectClass::building && o.id < 90);
        if (o.id != 1 && (flyer || obstacle)) clutter.insert(o.id);
    }
    Seen seen;
    const double half_field = 0.5 * std::min(s.sensor.scan->field_az_rad(), s.sensor.scan->field_el_rad());
    for (std::uint64_t k : frames) {
        const Frame f = renderer.render(k);
        for (const Return& r : f.returns) {
            REQUIRE(std::isfinite(r.range_m));
            REQUIRE(r.range_m > 0.0);
            seen.target += r.object_id == 1;
            seen.clutter += clutter.count(r.object_id) > 0;
            seen.map += r.object_id == scene::kBackgroundObjectId;
        }
        if (s.mount.cue_object_id == 0) continue;
        // The cue keeps the drone's box centre inside the field.
        for (const auto& g : f.ground_truth) {
            if (g.object_id != s.mount.cue_object_id) continue;
            const Eigen::Vector3d c = g.box_sensor.centre;
            const double az = std::atan2(c.y(), c.x()), el = std::atan2(c.z(), std::hypot(c.x(), c.y()));
            CHECK(std::abs(az - f.gimbal_az_rad) < half_field);
            CHECK(std::abs(el - f.gimbal_el_rad) < half_field);
        }
    }
    seen.clutter_objects = clutter.size();
    return seen;
}

bool have_autzen() {
    if (std::filesystem::exists(test::shared_data("autzen/autzen_trim.pcd"))) return true;
    test::skip("shared data not present: the Autzen variants are not rendered");
    return false;
}

}  // namespace

TEST_CASE("every shipped scenario renders with its drone in the field and its clutter visible", "[scenarios]") {
    const std::string name = GENERATE(as<std::string>{}, "default", "dataset1", "dataset2", "dataset3", "dataset4", "vlp16_drone");
    INFO(name);
    const Seen seen = render_and_check(load_scenario(kScenarios / (name + ".json")), {0, 1, 2});
    CHECK(seen.target > 0);
    if (seen.clutter_objects > 0) CHECK(seen.clutter > 0);
}

TEST_CASE("the datasets' Autzen variants render with the recorded map behind the drone", "[scenarios]") {
    if (!have_autzen()) return;
    // A frame of each where the map lies behind the drone (the sight line meets the ground on it).
    const auto [name, frame] = GENERATE(table<std::string, std::uint64_t>(
        {{"dataset1-autzen", 210}, {"dataset2-autzen", 0}, {"dataset3-autzen", 120}, {"dataset4-autzen", 150}}));
    INFO(name << " frame " << frame);
    const Scenario s = load_scenario(kScenarios / (name + ".json"));
    REQUIRE(s.scene.background);
    const Seen seen = render_and_check(s, {frame});
    CHECK(seen.map > 100);
    CHECK(seen.target > 0);
    CHECK(seen.clutter > 0);
}

TEST_CASE("the initial map a dataset carries holds the static scene and no target", "[scenarios]") {
    const std::string name = GENERATE(as<std::string>{}, "dataset4", "dataset2-autzen");
    INFO(name);
    if (name.ends_with("-autzen") && !have_autzen()) return;
    const test::ScratchDir dir;
    const Scenario s = load_scenario(kScenarios / (name + ".json"));
    DatasetOptions options;
    options.out_dir = dir / "d";
    options.frames = 2;
    const DatasetSummary summary = render_dataset(s, options);
    REQUIRE(summary.background_points > 0);
    std::set<std::uint32_t> moving;
    for (const auto& o : s.scene.objects)
        if (!o.trajectory.is_static()) moving.insert(o.id);
    std::size_t recorded_map = 0;
    for (const Return& r : read_frame_pcd(dir / "d" / "background.pcd")) {
        REQUIRE(moving.count(r.object_id) == 0);
        recorded_map += r.object_id == scene::kBackgroundObjectId;
    }
    // Over the real map, the sensor's own survey of it is what the detector subtracts.
    if (s.scene.background) CHECK(recorded_map > 1000);
}

TEST_CASE("the default scenario over the recorded Autzen map renders where the shared data is", "[scenarios]") {
    if (!have_autzen()) return;
    const Scenario s = load_scenario(kScenarios / "default-autzen.json");
    REQUIRE(s.scene.background);
    // Near the end of the approach the recorded map fills the field behind the drone.
    const Seen seen = render_and_check(s, {295});
    CHECK(seen.map > 1000);
    CHECK(seen.target > 0);
}
