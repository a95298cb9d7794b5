// Fog and cloud: free-path backscatter against the integral it estimates, attenuation of what
// lies behind, and a sensor that starts inside a cloud.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "ladarsim/scene/procedural_models.h"
#include "ladarsim/sensor_model/render/frame_renderer.h"
#include "ladarsim/sensor_model/signal/volume_echoes.h"
#include "../support/closed_form_scenario.h"
#include "../support/atmospheres.h"
#include "../support/scene_builders.h"

using namespace ladarsim;
using namespace ladarsim::sensor_model;
using namespace ladarsim::test;

namespace {

/// A closed box of fog (meteorological optical range `mor_m`) spanning x in [x0, x1].
std::shared_ptr<const scene::Model> fog_box(double x0, double x1, double half_width, double mor_m) {
    auto m = std::make_shared<scene::Model>(scene::make_box_building(x1 - x0, 2 * half_width, 2 * half_width));
    for (auto& material : m->materials) material = scene::fog_medium("fog", mor_m);
    return m;
}

}  // namespace

TEST_CASE("free-path sampling of backscatter is an unbiased estimate of its integral", "[volume]") {
    Sensor c = sensor_preset("paper_ladar");
    c.receiver.range_folding = false;
    const BeamReceiver receiver(c, test::vacuum(), false);
    const scene::Material fog = scene::fog_medium("fog", 150.0);  // alpha 0.02 /m, beta 3.1e-4 /m/sr
    const raytrace::VolumeSegment segment{9, 40.0, 140.0, fog.extinction_per_m, fog.backscatter_per_m_sr};
    const double area = c.optics.aperture_area_m2(), r2 = area / M_PI;
    const int draws = 200000;
    RandomSequence rng(11, RandomStream::volume_scatter, 0, 0);
    std::vector<BeamSurface> volumes;
    for (int i = 0; i < draws; ++i)
        add_volume_echoes(std::span(&segment, 1), 1e9, 1.0, 1.0 / draws, area, receiver, rng, volumes);
    REQUIRE(volumes.size() == 1);
    CHECK(volumes[0].source == ReturnSource::volume);
    CHECK(volumes[0].object_id == 9);
    double estimate = 0.0;
    for (const auto& e : volumes[0].echoes) {
        CHECK(e.range_m >= 40.0);
        CHECK(e.range_m <= 140.0);
        estimate += e.energy_j;
    }
    estimate /= draws;
    // The integral by the midpoint rule: int beta exp(-2 alpha s) pi r^2 / (R^2 + r^2) ds.
    double integral = 0.0;
    const int steps = 100000;
    const double ds = 100.0 / steps;
    for (int k = 0; k < steps; ++k) {
        const double s = (k + 0.5) * ds, range = 40.0 + s;
        integral += fog.backscatter_per_m_sr * std::exp(-2.0 * fog.extinction_per_m * s) * M_PI * r2 / (range * range + r2) * ds;
    }
    CHECK(estimate == Approx(integral).epsilon(0.01));
}

TEST_CASE("several free paths a sub-ray: the same expected echo and range, scattering about n times less", "[volume]") {
    // Each segment's n draws become one echo at their energy-weighted mean range, stretched by
    // their spread: over many sub-rays the energy and the energy-weighted range (the moments the
    // receiver takes of a volume's echoes) are those of the integral, and the echoes' ranges
    // scatter far less than one draw's do (stratified, about n times less for a smooth
    // distribution; independent draws would give sqrt(n)).
    Sensor c = sensor_preset("paper_ladar");
    c.receiver.range_folding = false;
    const BeamReceiver receiver(c, test::vacuum(), false);
    const scene::Material fog = scene::fog_medium("fog", 150.0);
    const raytrace::VolumeSegment segment{9, 40.0, 140.0, fog.extinction_per_m, fog.backscatter_per_m_sr};
    const double area = c.optics.aperture_area_m2(), r2 = area / M_PI;
    double integral = 0.0, range_integral = 0.0, second_integral = 0.0;
    const int steps = 100000;
    const double ds = 100.0 / steps;
    for (int k = 0; k < steps; ++k) {
        const double s = (k + 0.5) * ds, range = 40.0 + s;
        const double e = fog.backscatter_per_m_sr * std::exp(-2.0 * fog.extinction_per_m * s) * M_PI * r2 / (range * range + r2) * ds;
        integral += e;
        range_integral += e * range;
        second_integral += e * range * range;
    }
    const double mean_range = range_integral / integral;
    const double sigma = std::sqrt(second_integral / integral - mean_range * mean_range);
    auto run = [&](int free_paths) {
        const int sub_rays = 50000;
        RandomSequence rng(12, RandomStream::volume_scatter, 0, 0);
        std::vector<BeamSurface> volumes;
        for (int i = 0; i < sub_rays; ++i)
            add_volume_echoes(std::span(&segment, 1), 1e9, 1.0, 1.0 / sub_rays, area, receiver, rng, volumes, free_paths);
        REQUIRE(volumes.size() == 1);
        double energy = 0.0, moment = 0.0, second = 0.0, plain = 0.0, plain2 = 0.0;
        for (const Echo& e : volumes[0].echoes) {
            energy += e.energy_j;
            moment += e.energy_j * e.range_m;
            second += e.energy_j * (e.range_m * e.range_m + e.spread_m * e.spread_m);
            plain += e.range_m;
            plain2 += e.range_m * e.range_m;
        }
        const double n = static_cast<double>(volumes[0].echoes.size());
        CHECK(energy / sub_rays == Approx(integral).epsilon(0.01));
        CHECK(moment / energy == Approx(mean_range).epsilon(0.002));
        CHECK(std::sqrt(second / energy - (moment / energy) * (moment / energy)) == Approx(sigma).epsilon(0.02));
        return std::sqrt(plain2 / n - (plain / n) * (plain / n));  // the echoes' own scatter
    };
    const double one = run(1), sixteen = run(16);
    INFO("echo ranges scatter by " << one << " m with one free path, " << sixteen << " m with 16");
    CHECK(sixteen < one / 8.0);
}

TEST_CASE("a sensor inside fog: the wall behind is dimmed by exp(-2 tau), the fog itself returns", "[volume]") {
    Scenario s = test::closed_form_scenario();
    test::set_raster(s.sensor, 5, 1, 0.01, 0.01);
    const double mor = 100.0, fog_end = 30.0, wall = 80.0;
    // The fog box runs from x = -20 m (behind the sensor) to 30 m: the beams start inside it.
    s.scene.objects.push_back(object_at(1, fog_box(-20.0, fog_end, 10.0, mor), fixed_at(5.0, 0.0, -10.0), scene::ObjectClass::cloud));
    s.scene.objects.push_back(object_at(2, plate(40.0, 0.5), fixed_at(wall, 0.0, 0.0), scene::ObjectClass::building));
    FrameRenderer renderer(s);
    const Frame f = renderer.render(0);

    Scenario clear = s;
    clear.scene.objects.erase(clear.scene.objects.begin());
    FrameRenderer clear_renderer(clear);
    const Frame g = clear_renderer.render(0);

    const double alpha = scene::fog_medium("fog", mor).extinction_per_m;
    int walls = 0, fogs = 0;
    for (const Return& r : f.returns) {
        REQUIRE(std::isfinite(r.intensity));
        REQUIRE(std::isfinite(r.range_m));
        if (r.object_id == 2) {
            ++walls;
            const auto clear_wall = std::find_if(g.returns.begin(), g.returns.end(),
                                                 [&](const Return& x) { return x.column == r.column && x.object_id == 2; });
            REQUIRE(clear_wall != g.returns.end());
            // 30 m of fog along the (nearly axial) beam, both ways.
            CHECK(r.intensity / clear_wall->intensity == Approx(std::exp(-2.0 * alpha * fog_end)).epsilon(2e-3));
        } else {
            REQUIRE(r.object_id == 1);
            CHECK(r.source == ReturnSource::volume);
            CHECK(r.range_m < fog_end + 1.0);
            ++fogs;
        }
    }
    CHECK(walls == 5);
    CHECK(fogs >= 1);
}
