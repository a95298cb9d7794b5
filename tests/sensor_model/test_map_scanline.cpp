// A footprint over a recorded map integrated along lines (the default) and its dense reference,
// against closed forms: a flat wall of overlapping discs that fills every footprint returns the
// wall's range and the extended target's whole echo.
#include <catch2/catch.hpp>

#include <cmath>

#include "ladarsim/sensor_model/render/frame_renderer.h"
#include "../support/closed_form_scenario.h"
#include "../support/scene_builders.h"
#include "../support/sensors.h"

using namespace ladarsim;
using namespace ladarsim::sensor_model;
using namespace ladarsim::test;

namespace {

constexpr double kWallDistance = 500.0, kReflectance = 0.4;

/// A wall of discs facing the sensor at kWallDistance, on a 0.25 m grid, each of radius 0.2 m (over
/// the half diagonal, 0.177 m: no gaps), far wider than the raster's footprints.
Scenario disc_wall_scenario() {
    Scenario s = closed_form_scenario();
    set_raster(s.sensor, 16, 10, 0.05, 0.3);
    scene::BackgroundMap map;
    map.source = "disc wall";
    for (double y = -4.0; y <= 4.0; y += 0.25) {
        for (double z = -6.0; z <= 6.0; z += 0.25) {
            map.points_world.emplace_back(kWallDistance, y, z);
            map.normals.push_back(-Eigen::Vector3f::UnitX());
            map.radii_m.push_back(0.2f);
            map.reflectance.push_back(static_cast<float>(kReflectance));
        }
    }
    s.scene.background = std::move(map);
    return s;
}

}  // namespace

TEST_CASE("a flat wall of discs filling every footprint returns its range and the whole extended echo", "[footprint][map]") {
    Scenario adaptive = disc_wall_scenario(), reference = disc_wall_scenario();
    reference.render.footprint_samples = 1024;
    reference.render.footprint_map_lines = 64;
    for (const Scenario& s : {adaptive, reference}) {
        FrameRenderer renderer(s);
        const Frame f = renderer.render(0);
        REQUIRE(f.returns.size() == 160u);
        for (const Return& r : f.returns) {
            const double cos_axis = std::cos(r.beam_el_rad) * std::cos(r.beam_az_rad);
            const double range = kWallDistance / cos_axis;
            CHECK(r.object_id == scene::kBackgroundObjectId);
            CHECK(r.range_m == Approx(range).margin(1e-3));
            CHECK(r.intensity == Approx(extended_target_photoelectrons(s.sensor, kReflectance, cos_axis, range)).epsilon(1e-3));
        }
    }
}

TEST_CASE("the map's reference converges on a target thinner than its cells across a line", "[footprint][map]") {
    // A horizontal sliver 2 cm tall at 300 m (a wing edge-on) before the wall: 8 rays a line split
    // a footprint into cells 35 mm tall there, each given whole to whatever its ray met, so the
    // sliver took whole cells where rays hit it and nothing where they passed it by.
    auto sliver = std::make_shared<scene::Model>();
    for (const double y : {-0.3, 0.3})
        for (const double z : {-0.01, 0.01}) sliver->mesh.positions.emplace_back(0.0f, static_cast<float>(y), static_cast<float>(z));
    sliver->mesh.triangles = {{0u, 1u, 3u}, {0u, 3u, 2u}};
    sliver->mesh.triangle_material = {0, 0};
    sliver->materials = {scene::Material{"sliver", 0.5}};
    auto with_lines = [&](int lines) {
        Scenario s = disc_wall_scenario();
        s.render.noise = false;
        s.render.footprint_samples = 1024;
        s.render.footprint_map_lines = lines;
        s.scene.objects.push_back(object_at(7, sliver, fixed_at(300.0, 0.0, 0.01)));
        FrameRenderer renderer(s);
        double energy = 0.0;
        for (const Return& r : renderer.render(0).returns)
            if (r.object_id == 7) energy += r.intensity;
        return energy;
    };
    const double coarse = with_lines(128), fine = with_lines(256);
    REQUIRE(fine > 0.0);
    CHECK(coarse == Approx(fine).epsilon(0.05));
}
