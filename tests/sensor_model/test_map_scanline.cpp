// A footprint over a recorded map integrated along lines (the default) and its dense reference,
// against closed forms: a flat wall of overlapping discs that fills every footprint returns the
// wall's range and the extended target's whole echo.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <vector>

#include <Eigen/Geometry>

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

TEST_CASE("a target before the map: the map's echo in each beam is the whole echo less the target's share", "[footprint][map]") {
    // A 6 cm plate drifting at 300 m before the disc wall: in the beams it shares, the map behind
    // its outline is integrated over the outline's cells (or its line's lattice strata) by the
    // row's map lines, each carrying what its sub-ray left to the map. Whatever the split, the wall's
    // echo is the extended echo times the part of the beam the plate leaves: for a plate inside the
    // truncation, one minus the Gaussian's mass over its square (separable in footprint offsets).
    // (Measured: 32 beams over 3 frames, the worst 6e-4 of the beam off.)
    constexpr double kSide = 0.06, kPlateDistance = 300.0;
    const Eigen::Vector3d start(kPlateDistance, -0.15, 0.0), velocity(0.0, 1.0, 0.0);
    Scenario s = disc_wall_scenario();
    s.scene.objects.push_back(object_at(7, plate(kSide, 0.5), sliding(start, velocity)));
    s.render.frames = 3;
    FrameRenderer renderer(s);
    std::vector<Return> returns;
    for (std::uint64_t frame = 0; frame < 3; ++frame) {
        const Frame f = renderer.render(frame);
        returns.insert(returns.end(), f.returns.begin(), f.returns.end());
    }
    const double w = 0.5 * s.sensor.transmitter.divergence_mrad * 1e-3, sigma = 0.5 * w, r_max = s.render.footprint_truncation * w;
    const double captured = 1.0 - std::exp(-2.0 * s.render.footprint_truncation * s.render.footprint_truncation);
    auto phi = [&](double offset) { return 0.5 * std::erfc(-offset / (sigma * std::sqrt(2.0))); };
    int shared = 0;
    double worst = 0.0, sum = 0.0;
    for (const Return& r : returns) {
        if (r.object_id != scene::kBackgroundObjectId) continue;
        const double cos_axis = std::cos(r.beam_el_rad) * std::cos(r.beam_az_rad);
        CHECK(r.range_m == Approx(kWallDistance / cos_axis).margin(1e-3));
        // The plate's corners in footprint offsets at the beam's time (x along the beam, y left, z up).
        const Eigen::Matrix3d beam_from_world =
            (Eigen::AngleAxisd(r.beam_az_rad, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-r.beam_el_rad, Eigen::Vector3d::UnitY()))
                .toRotationMatrix()
                .transpose();
        const Eigen::Vector3d centre = start + velocity * r.time_s;
        double x_lo = 1e9, x_hi = -1e9, y_lo = 1e9, y_hi = -1e9;
        bool inside = true;
        for (const double dy : {-0.5 * kSide, 0.5 * kSide})
            for (const double dz : {-0.5 * kSide, 0.5 * kSide}) {
                const Eigen::Vector3d v = beam_from_world * (centre + Eigen::Vector3d(0.0, dy, dz));
                const double x = std::atan2(v.y(), v.x()), y = std::atan2(v.z(), v.x());
                x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x), y_lo = std::min(y_lo, y), y_hi = std::max(y_hi, y);
                inside = inside && std::hypot(x, y) < r_max;
            }
        const double share = inside ? (phi(x_hi) - phi(x_lo)) * (phi(y_hi) - phi(y_lo)) / captured : 0.0;
        if (!(share > 0.01) || !inside) continue;
        ++shared;
        const double left = r.intensity / extended_target_photoelectrons(s.sensor, kReflectance, cos_axis, r.range_m);
        const double error = left - (1.0 - share);
        UNSCOPED_INFO("row " << r.row << " column " << r.column << ": plate's share " << share << ", map's " << left);
        worst = std::max(worst, std::abs(error));
        sum += error;
    }
    INFO(shared << " beams shared with the plate; worst error " << worst << " of the beam, mean " << sum / std::max(shared, 1));
    REQUIRE(shared >= 10);
    CHECK(worst < 0.005);
    CHECK(std::abs(sum / shared) < 0.001);
}

TEST_CASE("the map behind a target's outline is what its shape leaves, not an even share of the outline", "[footprint][map]") {
    // A triangle drifting at 300 m before a wall whose lower half stands 2 m nearer: its outline
    // (its bounding square) straddles the step, and it hides three quarters of the square's upper
    // half but one quarter of the lower. Each half's return must carry what the triangle leaves of
    // it (against 16,384 sub-rays a beam, the map by 256 lines), not the outline's map spread
    // evenly over both. Measured: 36 beams over 3 frames (the line's lattice takes them), worst
    // 0.26 % of the beam; 4.7 % when the lattice brought the map over its whole outline at the
    // share its sub-rays gave the map.
    auto triangle = std::make_shared<scene::Model>();
    for (const auto& [y, z] : {std::pair{-0.03, 0.03}, std::pair{0.03, 0.03}, std::pair{-0.03, -0.03}})
        triangle->mesh.positions.emplace_back(0.0f, static_cast<float>(y), static_cast<float>(z));
    triangle->mesh.triangles = {{0u, 1u, 2u}};
    triangle->mesh.triangle_material = {0};
    triangle->materials = {scene::Material{"triangle", 0.5}};
    // Both on the axis of the raster's row just above the middle (its 10 rows over 0.3 deg): the
    // nearer discs' scalloped top (their centres 0.25 m below the farther ones', radius 0.2 m)
    // about 0.07 m under the lowest farther centre.
    const double kRowElevation = 0.5 * 0.3 / 10 * std::numbers::pi / 180.0, kStepHeight = kWallDistance * std::tan(kRowElevation) + 0.07;
    auto render = [&](int samples, int lines) {
        Scenario s = disc_wall_scenario();
        for (Eigen::Vector3d& p : s.scene.background->points_world) {
            if (p.z() < 0.0) p.x() -= 2.0;
            p.z() += kStepHeight;
        }
        s.render.noise = false;
        s.render.frames = 3;
        if (samples > 0) {
            s.render.footprint_samples = samples;
            s.render.footprint_map_lines = lines;
        }
        s.scene.objects.push_back(object_at(7, triangle, sliding({300.0, -0.15, 300.0 * std::tan(kRowElevation)}, {0.0, 1.0, 0.0})));
        FrameRenderer renderer(s);
        // Per beam the triangle returns in, the map's energy nearer and farther than the step.
        std::map<std::uint64_t, std::array<double, 2>> halves;
        std::set<std::uint64_t> shared;
        for (std::uint64_t frame = 0; frame < 3; ++frame)
            for (const Return& r : renderer.render(frame).returns) {
                const std::uint64_t beam = frame << 32 | std::uint64_t{r.row} << 16 | r.column;
                const double cos_axis = std::cos(r.beam_el_rad) * std::cos(r.beam_az_rad);
                if (r.object_id == 7) shared.insert(beam);
                if (r.object_id == scene::kBackgroundObjectId) halves[beam][r.range_m * cos_axis < kWallDistance - 1.0 ? 0 : 1] += r.intensity;
            }
        std::erase_if(halves, [&](const auto& b) { return !shared.contains(b.first); });
        return halves;
    };
    const auto got = render(0, 0), want = render(16384, 256), finer = render(4096, 128);
    // Over beams the triangle shares, the largest error of either half, in the beam's whole echo.
    auto worst = [&](const auto& a, const auto& b, int& shared) {
        double e = 0.0;
        shared = 0;
        for (const auto& [beam, w] : b) {
            const auto it = a.find(beam);
            if (it == a.end()) continue;
            ++shared;
            const double whole = w[0] + w[1];
            for (int h = 0; h < 2; ++h) e = std::max(e, std::abs(it->second[h] - w[h]) / whole);
        }
        return e;
    };
    int shared = 0, shared_refs = 0;
    const double error = worst(got, want, shared), references = worst(finer, want, shared_refs);
    INFO(shared << " beams shared with the triangle: worst " << error << " of the beam, the two references " << references);
    REQUIRE(shared >= 10);
    CHECK(references < 0.002);
    CHECK(error < 0.01);
}
