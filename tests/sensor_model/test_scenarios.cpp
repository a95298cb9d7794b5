// The shipped scenarios: each loads, renders, keeps its drone in the field, and shows the clutter
// it promises; the initial map holds no target.
#include <catch2/catch.hpp>

#include <cmath>
#include <set>

#include "ladarsim/sensor_model/dataset.h"
#include "ladarsim/sensor_model/frame_renderer.h"
#include "ladarsim/sensor_model/pcd_file.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;
using namespace ladarsim::sensor_model;

namespace {
const std::filesystem::path kScenarios = std::filesystem::path(LADARSIM_SOURCE_DIR) / "assets/scenarios";
}

TEST_CASE("every shipped scenario renders with its drone in the field and its clutter visible", "[scenarios]") {
    const std::string name = GENERATE(as<std::string>{}, "default", "dataset1", "dataset2", "dataset3", "dataset4", "vlp16_drone");
    INFO(name);
    const Scenario s = load_scenario(kScenarios / (name + ".json"));
    FrameRenderer renderer(s);
    std::set<std::uint32_t> clutter;
    for (const auto& o : s.scene.objects)
        if (o.id != 1 && !o.trajectory.is_static() && o.object_class != scene::ObjectClass::drone) clutter.insert(o.id);
    for (const auto& o : s.scene.objects)
        if (o.object_class == scene::ObjectClass::cloud || (o.object_class == scene::ObjectClass::building && o.id < 90)) clutter.insert(o.id);
    int target_returns = 0, clutter_returns = 0;
    const double half_field = 0.5 * std::min(s.sensor.field_az_deg, s.sensor.field_el_deg) * M_PI / 180.0;
    for (std::uint64_t k = 0; k < 3; ++k) {
        const Frame f = renderer.render(k);
        for (const Return& r : f.returns) {
            target_returns += r.object_id == 1;
            clutter_returns += clutter.count(r.object_id) > 0;
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
    CHECK(target_returns > 0);
    if (!clutter.empty()) CHECK(clutter_returns > 0);
}

TEST_CASE("the initial map a dataset carries holds the static scene and no target", "[scenarios]") {
    const test::ScratchDir dir;
    const Scenario s = load_scenario(kScenarios / "dataset4.json");
    DatasetOptions options;
    options.out_dir = dir / "d4";
    options.frames = 2;
    const DatasetSummary summary = render_dataset(s, options);
    REQUIRE(summary.background_points > 0);
    std::set<std::uint32_t> moving;
    for (const auto& o : s.scene.objects)
        if (!o.trajectory.is_static()) moving.insert(o.id);
    for (const Return& r : read_frame_pcd(dir / "d4" / "background.pcd")) REQUIRE(moving.count(r.object_id) == 0);
}

TEST_CASE("the default scenario over the recorded Autzen map renders where the shared data is", "[scenarios]") {
    if (!std::filesystem::exists(std::filesystem::path(LADARSIM_SHARED_DIR) / "data/autzen/autzen_trim.pcd")) {
        WARN("shared data not present: default-autzen.json not rendered");
        return;
    }
    const Scenario s = load_scenario(kScenarios / "default-autzen.json");
    REQUIRE(s.scene.background);
    FrameRenderer renderer(s);
    // Near the end of the approach the recorded map fills the field behind the drone.
    const Frame f = renderer.render(295);
    int map_returns = 0, drone_returns = 0;
    for (const Return& r : f.returns) {
        map_returns += r.object_id == scene::kBackgroundObjectId;
        drone_returns += r.object_id == 1;
    }
    CHECK(map_returns > 1000);
    CHECK(drone_returns > 0);
}
