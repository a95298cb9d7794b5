#include "scaling.h"

#include <cmath>
#include <numbers>
#include <random>

#include "bench_frames.h"
#include "ladarsim/raytrace/traced_scene.h"
#include "ladarsim/sensor_model/sensor/galvo_raster.h"
#include "ladarsim/core/units.h"

namespace ladarsim::bench {

namespace {

using nlohmann::json;

/// Rays fanning over 0.5 x 0.5 deg around a direction 1 deg below the horizon from 3 m up: they
/// land 170 m out and beyond, on whatever the scene puts there.
std::vector<raytrace::Ray> fan(std::size_t count) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    std::vector<raytrace::Ray> rays(count);
    for (raytrace::Ray& r : rays) {
        const double az = 0.5 * kDeg * u(rng), el = -1.0 * kDeg + 0.5 * kDeg * u(rng);
        r.origin_world = Eigen::Vector3d(0.0, 0.0, 3.0);
        r.direction = Eigen::Vector3d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
        r.max_range_m = 3000.0;
    }
    return rays;
}

/// Rays per second through TracedScene, in streams of 64 like a footprint's.
double rays_per_second(const raytrace::TracedScene& traced, const std::vector<raytrace::Ray>& rays) {
    std::vector<std::optional<raytrace::Hit>> hits(64);
    const auto start = Clock::now();
    for (std::size_t i = 0; i + 64 <= rays.size(); i += 64) traced.trace({rays.data() + i, 64}, hits);
    return double(rays.size() / 64 * 64) / seconds_since(start);
}

/// A rolling height field of n x n quads (2 n^2 triangles) over 100..1100 m x -300..300 m.
scene::Scene terrain_of(int n) {
    auto model = std::make_shared<scene::Model>();
    model->materials.push_back(scene::Material{});
    auto& mesh = model->mesh;
    for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= n; ++j) {
            const float x = 100.0f + 1000.0f * i / n, y = -300.0f + 600.0f * j / n;
            mesh.positions.emplace_back(x, y, 2.0f * std::sin(0.05f * x) * std::cos(0.07f * y));
        }
    }
    auto at = [n](int i, int j) { return static_cast<std::uint32_t>(i * (n + 1) + j); };
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            mesh.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
            mesh.triangle_material.push_back(0);
            mesh.triangle_material.push_back(0);
        }
    }
    scene::SceneObject terrain;
    terrain.id = 1;
    terrain.object_class = scene::ObjectClass::terrain;
    terrain.model = model;
    terrain.trajectory = scene::Trajectory::fixed(scene::Pose{});
    scene::Scene s;
    s.objects.push_back(terrain);
    return s;
}

/// A recorded-map stand-in: `count` points on the same rolling ground, with upward discs sized
/// to their spacing.
scene::Scene map_of(std::size_t count) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    scene::BackgroundMap map;
    map.source = "synthetic";
    const double area = 1000.0 * 600.0;
    const float radius = static_cast<float>(std::sqrt(area / count / std::numbers::pi) * 1.5);
    map.points_world.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
        const double x = 100.0 + 1000.0 * u(rng), y = -300.0 + 600.0 * u(rng);
        map.points_world.emplace_back(x, y, 2.0 * std::sin(0.05 * x) * std::cos(0.07 * y));
    }
    map.normals.assign(count, Eigen::Vector3f::UnitZ());
    map.radii_m.assign(count, radius);
    map.reflectance.assign(count, 0.3f);
    scene::Scene s;
    s.background = std::move(map);
    return s;
}

}  // namespace

json scaling(const sensor_model::Scenario& scenario, const BenchOptions& options) {
    json result;
    const std::uint64_t frame = static_cast<std::uint64_t>(scenario.render.frames / 2);

    // Denser rasters of the same field: a galvo raster's beam counts scale; other patterns are
    // what their calibration says and are timed as they are.
    const auto* galvo = dynamic_cast<const sensor_model::GalvoRaster*>(scenario.sensor.scan.get());
    json beams = json::array();
    for (const int factor : galvo ? std::vector<int>{1, 2, 4} : std::vector<int>{1}) {
        sensor_model::Scenario s = scenario;
        if (galvo) {
            sensor_model::GalvoRaster::Parameters p = galvo->parameters();
            p.beams_az *= factor;
            p.beams_el *= factor;
            s.sensor.scan = std::make_shared<sensor_model::GalvoRaster>(p);
        }
        const sensor_model::ScanPattern& scan = *s.sensor.scan;
        options.progress("scaling: " + std::to_string(scan.columns()) + " x " + std::to_string(scan.rows()) + " beams");
        const Rendering r = render_frames(s, {frame, frame + 1, frame + 2});
        beams.push_back({{"beams_per_frame", scan.beam_count()},
                         {"seconds_per_frame", r.seconds / 3.0},
                         {"beams_per_s", r.beams_per_second()}});
    }
    result["beams"] = beams;

    const std::vector<raytrace::Ray> rays = fan(options.quick ? 200'000 : 1'000'000);
    json triangles = json::array();
    for (const int n : {70, 224, 707, 2236}) {
        if (options.quick && n > 707) break;
        options.progress("scaling: " + std::to_string(2 * n * n) + " triangles");
        const scene::Scene s = terrain_of(n);
        const raytrace::TracedScene traced(s, Eigen::Vector3d(0.0, 0.0, 3.0));
        triangles.push_back({{"triangles", 2 * n * n}, {"rays_per_s", rays_per_second(traced, rays)}});
    }
    result["triangles"] = triangles;

    json maps = json::array();
    for (const std::size_t count : {std::size_t{100'000}, std::size_t{1'000'000}, std::size_t{10'000'000}}) {
        if (options.quick && count > 1'000'000) break;
        options.progress("scaling: background map of " + std::to_string(count) + " points");
        const std::uint64_t before = resident_bytes();
        const scene::Scene s = map_of(count);
        const auto start = Clock::now();
        const raytrace::TracedScene traced(s, Eigen::Vector3d(0.0, 0.0, 3.0));
        const double build_s = seconds_since(start);
        maps.push_back({{"points", count},
                        {"build_s", build_s},
                        {"resident_mb", double(resident_bytes() - before) / (1 << 20)},
                        {"rays_per_s", rays_per_second(traced, rays)}});
    }
    result["background_map"] = maps;
    return result;
}

}  // namespace ladarsim::bench
