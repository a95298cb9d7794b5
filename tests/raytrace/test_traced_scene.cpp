// TracedScene against closed-form ray/plane, ray/sphere and ray/disc distances.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "ladarsim/raytrace/traced_scene.h"
#include "../support/rays.h"
#include "../support/scene_builders.h"

using namespace ladarsim;
using namespace ladarsim::test;
using raytrace::Ray;
using raytrace::TracedScene;

namespace {

/// Distance along a unit ray to the near side of a sphere; the ray must hit it.
double sphere_distance(const Ray& r, const Eigen::Vector3d& centre, double radius) {
    const Eigen::Vector3d oc = r.origin_world - centre;
    const double b = oc.dot(r.direction);
    const double c = oc.squaredNorm() - radius * radius;
    return -b - std::sqrt(b * b - c);
}

}  // namespace

TEST_CASE("ranges to a tilted plane at 10 m and 2 km match the closed form to 1 mm", "[traced_scene]") {
    const double distance = GENERATE(10.0, 2000.0);
    const double tilt_deg = 35.0;
    const Eigen::Quaterniond tilt(Eigen::AngleAxisd(tilt_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
    scene::Scene scene;
    scene.objects.push_back(object_at(1, plate(0.5 * distance, 0.4),
                                      scene::Trajectory::fixed(scene::Pose{{distance, 0, 0}, tilt})));
    const Eigen::Vector3d sensor(0.0, 0.0, 0.0);
    TracedScene traced(scene, sensor);
    const Eigen::Vector3d n = tilt * Eigen::Vector3d::UnitX();

    for (double y : {-0.1, 0.0, 0.07}) {
        for (double z : {-0.1, 0.03, 0.11}) {
            const Ray r = ray_from(sensor, {distance, y * distance, z * distance});
            const auto hit = traced.trace(r);
            REQUIRE(hit);
            CHECK(std::abs(hit->range_m - plane_distance(r, {distance, 0, 0}, n)) < 1e-3);
            CHECK(hit->object_id == 1u);
            CHECK(hit->reflectance == Approx(0.4f));
            // Facing the ray, and the incidence cosine is the angle to the plane's normal.
            CHECK(hit->normal_world.cast<double>().dot(r.direction) < 0.0);
            CHECK(hit->cos_incidence == Approx(std::abs(r.direction.dot(n))).margin(1e-6));
        }
    }
}

TEST_CASE("ranges to a sphere at 10 m and 2 km match the closed form to 1 mm", "[traced_scene]") {
    const double distance = GENERATE(10.0, 2000.0);
    const double radius = 0.5;
    const auto sphere = icosphere(radius, 5, 0.2);
    // The facets' own departure from the sphere is part of the error budget: keep it small.
    const double sag = max_facet_sag(*sphere, radius);
    REQUIRE(sag < 0.2e-3);  // a fifth of the 1 mm budget

    scene::Scene scene;
    scene.objects.push_back(object_at(1, sphere, fixed_at(distance, 0.0, 0.0)));
    const Eigen::Vector3d sensor(0.0, 0.0, 0.0);
    TracedScene traced(scene, sensor);
    const Eigen::Vector3d centre(distance, 0.0, 0.0);
    for (double dy : {0.0, 0.2, -0.35}) {
        for (double dz : {0.0, 0.1, 0.3}) {
            const Ray r = ray_from(sensor, centre + Eigen::Vector3d(0.0, dy, dz));
            const auto hit = traced.trace(r);
            REQUIRE(hit);
            CHECK(std::abs(hit->range_m - sphere_distance(r, centre, radius)) < 1e-3);
        }
    }
    // Just past the limb: a miss.
    CHECK_FALSE(traced.trace(ray_from(sensor, centre + Eigen::Vector3d(0.0, radius * 1.01, 0.0))));
}

TEST_CASE("geo-referenced coordinates: a sensor 4000 km from the world origin still ranges to 1 mm", "[traced_scene]") {
    const Eigen::Vector3d sensor(512345.678, 4123456.789, 231.5);
    const Eigen::Vector3d target = sensor + Eigen::Vector3d(1500.0, 700.0, 40.0);
    scene::Scene scene;
    scene.objects.push_back(object_at(7, plate(20.0, 0.3), fixed_at(target.x(), target.y(), target.z())));
    TracedScene traced(scene, sensor);
    const Ray r = ray_from(sensor, target + Eigen::Vector3d(0.0, 3.0, -2.0));
    const auto hit = traced.trace(r);
    REQUIRE(hit);
    CHECK(std::abs(hit->range_m - plane_distance(r, target, Eigen::Vector3d::UnitX())) < 1e-3);

    // A ray whose origin is not the scene origin (a second sensor 300 m away) is exact too.
    const Ray other = ray_from(sensor + Eigen::Vector3d(-300.0, 12.345, 0.5), target);
    const auto hit2 = traced.trace(other);
    REQUIRE(hit2);
    CHECK(std::abs(hit2->range_m - plane_distance(other, target, Eigen::Vector3d::UnitX())) < 1e-3);
}

TEST_CASE("a moving target is hit where its trajectory puts it at each ray's time", "[traced_scene]") {
    // A plate receding along the line of sight at 80 m/s and drifting sideways at 120 m/s.
    const Eigen::Vector3d start(500.0, -1.0, 0.0), velocity(80.0, 120.0, 0.0);
    scene::Scene scene;
    scene.objects.push_back(object_at(2, plate(4.0, 0.5), sliding(start, velocity)));
    const Eigen::Vector3d sensor = Eigen::Vector3d::Zero();
    TracedScene traced(scene, sensor);
    const double begin = 1.0, end = 1.05;
    traced.set_time_window(begin, end, 2);  // linear motion: interpolation between two steps is exact

    for (double t : {1.0, 1.013, 1.031, 1.05}) {
        const Eigen::Vector3d centre = start + t * velocity;
        const Ray r = ray_from(sensor, centre + Eigen::Vector3d(0.0, 0.5, 0.2), t);
        const auto hit = traced.trace(r);
        REQUIRE(hit);
        CHECK(std::abs(hit->range_m - plane_distance(r, centre, Eigen::Vector3d::UnitX())) < 1e-3);
        // Aimed where the plate was at the window's start: hit exactly when that ray crosses the
        // plate's square at time t.
        const Ray stale = ray_from(sensor, start + begin * velocity, t);
        const Eigen::Vector3d p = stale.origin_world + plane_distance(stale, centre, Eigen::Vector3d::UnitX()) * stale.direction;
        const bool inside = std::abs(p.y() - centre.y()) < 2.0 && std::abs(p.z() - centre.z()) < 2.0;
        CHECK(traced.trace(stale).has_value() == inside);
    }
}

TEST_CASE("instances of one model carry their own id, class, scale and reflectance", "[traced_scene]") {
    const auto model = plate(1.0, 0.25);
    scene::Scene scene;
    scene.objects.push_back(object_at(3, model, sliding({100.0, 0.0, 0.0}, {0.0, 0.0, 1.0}), scene::ObjectClass::bird));
    scene::SceneObject big = object_at(4, model, sliding({100.0, 20.0, 0.0}, {0.0, 0.0, 1.0}), scene::ObjectClass::plane);
    big.scale = 4.0;
    scene.objects.push_back(big);
    TracedScene traced(scene, Eigen::Vector3d::Zero());

    const auto small_hit = traced.trace(ray_from({0, 0, 0}, {100.0, 0.0, 0.0}));
    REQUIRE(small_hit);
    CHECK(small_hit->object_id == 3u);
    CHECK(small_hit->object_class == scene::ObjectClass::bird);
    // 1.5 m off the centre: outside the unit plate, inside the one scaled by 4.
    CHECK_FALSE(traced.trace(ray_from({0, 0, 0}, {100.0, 1.5, 0.0})));
    const auto big_hit = traced.trace(ray_from({0, 0, 0}, {100.0, 21.5, 0.0}));
    REQUIRE(big_hit);
    CHECK(big_hit->object_id == 4u);
    CHECK(big_hit->object_class == scene::ObjectClass::plane);
    CHECK(big_hit->reflectance == Approx(0.25f));
}

TEST_CASE("background points are oriented discs of their own radius, normal and reflectance", "[traced_scene]") {
    scene::Scene scene;
    scene::BackgroundMap map;
    // One disc on the ground 50 m ahead, normal tilted 20 degrees from up towards the sensor.
    const Eigen::Vector3d centre(50.0, 0.0, -2.0);
    const Eigen::Vector3d n = Eigen::Vector3d(-std::sin(20 * M_PI / 180), 0.0, std::cos(20 * M_PI / 180));
    map.points_world = {centre};
    map.normals = {n.cast<float>()};
    map.radii_m = {0.5f};
    map.reflectance = {0.6f};
    scene.background = map;
    TracedScene traced(scene, Eigen::Vector3d::Zero());

    const Ray r = ray_from({0, 0, 0}, centre + Eigen::Vector3d(0.0, 0.3, 0.0));
    const auto hit = traced.trace(r);
    REQUIRE(hit);
    CHECK(hit->object_id == scene::kBackgroundObjectId);
    CHECK(hit->object_class == scene::ObjectClass::background);
    CHECK(hit->reflectance == Approx(0.6f));
    CHECK(std::abs(hit->range_m - plane_distance(r, centre, n)) < 1e-4);
    CHECK(hit->cos_incidence == Approx(std::abs(r.direction.dot(n))).margin(1e-6));
    // 0.55 m from the centre within the disc's plane: outside the disc.
    CHECK_FALSE(traced.trace(ray_from({0, 0, 0}, centre + Eigen::Vector3d(0.0, 0.55, 0.0))));
}

TEST_CASE("misses, range limits and streams", "[traced_scene]") {
    scene::Scene scene;
    scene.objects.push_back(object_at(1, plate(10.0, 0.3), fixed_at(100.0, 0, 0)));
    TracedScene traced(scene, Eigen::Vector3d::Zero());

    CHECK_FALSE(traced.trace(ray_from({0, 0, 0}, {-100.0, 0, 0})));  // looking away
    Ray short_ray = ray_from({0, 0, 0}, {100.0, 0, 0});
    short_ray.max_range_m = 99.0;
    CHECK_FALSE(traced.trace(short_ray));

    // A stream gives exactly what single rays give.
    std::vector<Ray> rays;
    for (int i = 0; i < 64; ++i) rays.push_back(ray_from({0, 0, 0}, {100.0, -8.1 + 0.25 * i, 0.1 * (i % 7)}));
    std::vector<std::optional<raytrace::Hit>> hits(rays.size());
    traced.trace(rays, hits);
    int hit_count = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const auto single = traced.trace(rays[i]);
        REQUIRE(single.has_value() == hits[i].has_value());
        if (single) {
            ++hit_count;
            CHECK(single->range_m == hits[i]->range_m);
        }
    }
    CHECK(hit_count == 40);  // |y| < 5 at y = -8.1 + 0.25 i: i = 13..52
    CHECK_THROWS(traced.set_time_window(1.0, 0.5, 2));
}

TEST_CASE("Embree's own errors arrive as exceptions carrying its message", "[traced_scene]") {
    scene::Scene scene;
    scene.objects.push_back(object_at(1, plate(1.0, 0.3), sliding({50.0, 0, 0}, {0, 1, 0})));
    TracedScene traced(scene, Eigen::Vector3d::Zero());
    // Embree accepts at most 129 time steps per geometry; it reports more through its callback.
    try {
        traced.set_time_window(0.0, 1.0, 1000);
        FAIL("no exception for 1000 time steps");
    } catch (const std::runtime_error& e) {
        CHECK_THAT(e.what(), Catch::Matchers::Contains("Embree") && Catch::Matchers::Contains("invalid timestep"));
    }
}

TEST_CASE("volumes: where a ray runs inside fog, from outside and from inside", "[traced_scene]") {
    // A 10 m fog cube centred 50 m ahead: two triangles per face, outward, from a box plate set.
    auto cube = std::make_shared<scene::Model>();
    for (int k = 0; k < 8; ++k)
        cube->mesh.positions.emplace_back(k & 1 ? 5.0f : -5.0f, k & 2 ? 5.0f : -5.0f, k & 4 ? 5.0f : -5.0f);
    cube->mesh.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                            {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
    cube->mesh.triangle_material.assign(12, 0);
    cube->materials = {scene::fog_medium("fog", 300.0)};
    REQUIRE(cube->is_volume());
    scene::Scene scene;
    scene.objects.push_back(object_at(5, cube, fixed_at(50.0, 0, 0), scene::ObjectClass::cloud));
    scene.objects.push_back(object_at(6, plate(30.0, 0.3), fixed_at(80.0, 0, 0)));
    TracedScene traced(scene, Eigen::Vector3d::Zero());
    REQUIRE(traced.has_volumes());

    // Surfaces see through the fog: the plate behind it is the hit.
    const Ray through = ray_from({0, 0, 0}, {80.0, 1.0, 0.5});
    const auto hit = traced.trace(through);
    REQUIRE(hit);
    CHECK(hit->object_id == 6u);
    const auto outside = traced.volumes_along(through);
    REQUIRE(outside.size() == 1);
    CHECK(outside[0].object_id == 5u);
    CHECK(outside[0].enter_m == Approx(plane_distance(through, {45.0, 0, 0}, Eigen::Vector3d::UnitX())).margin(1e-4));
    CHECK(outside[0].exit_m == Approx(plane_distance(through, {55.0, 0, 0}, Eigen::Vector3d::UnitX())).margin(1e-4));
    CHECK(outside[0].extinction_per_m == Approx(std::log(20.0) / 300.0));

    // Starting inside: the segment opens at 0.
    const Ray from_inside = ray_from({50.0, 0, 0}, {80.0, 0, 0});
    const auto inside = traced.volumes_along(from_inside);
    REQUIRE(inside.size() == 1);
    CHECK(inside[0].enter_m == 0.0);
    CHECK(inside[0].exit_m == Approx(5.0).margin(1e-4));

    // Missing the cube: nothing.
    CHECK(traced.volumes_along(ray_from({0, 0, 0}, {50.0, 20.0, 0})).empty());

    // Through the edge two triangles of the near face share (its diagonal y = z) and through the
    // cube's own edges: a boundary crossed there must still count as entering. A ray slipping
    // between the two triangles would find only the exit and start "inside" at 0 m, filling the
    // 45 m in front of the cloud with fog.
    int crossings = 0;
    for (int i = -400; i <= 400; ++i) {
        const double s = 4.99 * i / 400.0;
        for (const Eigen::Vector3d& target : {Eigen::Vector3d(45.0, s, s), Eigen::Vector3d(45.0, 5.0, s), Eigen::Vector3d(45.0, s, -5.0)}) {
            const Ray edge = ray_from({0, 0, 0}, target);
            const auto segments = traced.volumes_along(edge);
            if (segments.empty()) continue;  // grazing the cube's outline: in or out are both honest
            INFO("towards " << target.transpose() << ": " << segments[0].enter_m << " to " << segments[0].exit_m);
            REQUIRE(segments.size() == 1);
            ++crossings;
            REQUIRE(segments[0].enter_m == Approx(plane_distance(edge, {45.0, 0, 0}, Eigen::Vector3d::UnitX())).margin(1e-3));
        }
    }
    CHECK(crossings > 801);
}

TEST_CASE("volumes: rays grazing a cloud's outline never start inside it, but a sensor in fog does", "[traced_scene]") {
    // An icosphere cloud of radius 10 m 1.4 km out (float vertices there are 0.1 mm apart) and
    // rays from the sensor aimed at its outline, where entry and exit nearly coincide and rounding
    // can order them either way: a segment may be short or absent, but never open at the sensor.
    auto sphere = std::make_shared<scene::Model>(*icosphere(10.0, 3, 0.3));
    sphere->materials = {scene::fog_medium("cloud", 50.0)};
    scene::Scene scene;
    const Eigen::Vector3d centre(1400.0, 37.0, -110.0);
    scene.objects.push_back(object_at(3, sphere, fixed_at(centre.x(), centre.y(), centre.z()), scene::ObjectClass::cloud));
    {
        TracedScene traced(scene, Eigen::Vector3d::Zero());
        const Eigen::Vector3d axis = centre.normalized();
        const Eigen::Vector3d u = axis.cross(Eigen::Vector3d::UnitZ()).normalized(), v = axis.cross(u);
        int cut = 0;
        for (int k = 0; k < 20000; ++k) {
            // Just inside the circumscribed outline, where the rays cross facets' edges obliquely.
            const double a = 2.0 * M_PI * k / 20000.0, offset = 10.0 * (0.97 + 0.03 * std::fmod(k * 0.618034, 1.0));
            const Ray r = ray_from(Eigen::Vector3d::Zero(), centre + offset * (std::cos(a) * u + std::sin(a) * v));
            for (const auto& s : traced.volumes_along(r)) {
                REQUIRE(s.enter_m > 1300.0);
                REQUIRE(s.exit_m >= s.enter_m);
                ++cut;
            }
        }
        CHECK(cut > 1000);
    }
    // The same cloud with the sensor inside it: every direction starts in the fog.
    TracedScene inside(scene, centre + Eigen::Vector3d(1.0, -2.0, 0.5));
    for (const Eigen::Vector3d& d : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0.3, -0.4, 0.866)}) {
        const Ray r = ray_from(centre + Eigen::Vector3d(1.0, -2.0, 0.5), centre + Eigen::Vector3d(1.0, -2.0, 0.5) + d);
        const auto segments = inside.volumes_along(r);
        REQUIRE(segments.size() == 1);
        CHECK(segments[0].enter_m == 0.0);
        CHECK(segments[0].exit_m > 7.0);
        CHECK(segments[0].exit_m < 12.5);
    }
}

TEST_CASE("object_bounds_near: every object a cone can meet, against testing each object", "[traced_scene]") {
    // Plates and spheres, small and large, fixed and moving fast, scattered around the sensor.
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    scene::Scene scene;
    for (std::uint32_t id = 1; id <= 40; ++id) {
        const Eigen::Vector3d at(300.0 * u(rng), 300.0 * u(rng), 50.0 * u(rng));
        const auto model = id % 2 ? plate(0.2 + 5.0 * (u(rng) + 1.0), 0.3) : icosphere(0.1 + 2.0 * (u(rng) + 1.0), 1, 0.3);
        scene.objects.push_back(object_at(id, model, id % 3 ? sliding(at, 40.0 * Eigen::Vector3d(u(rng), u(rng), u(rng)))
                                                            : fixed_at(at.x(), at.y(), at.z())));
    }
    const Eigen::Vector3d sensor(3.0, -2.0, 1.0);
    TracedScene traced(scene, sensor);
    traced.set_time_window(2.0, 2.5, 3);
    std::vector<raytrace::ObjectBounds> all, near;
    int met = 0, culled = 0;
    for (int beam = 0; beam < 4000; ++beam) {
        const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
        const double half_angle = beam % 2 ? 1e-3 : 0.05, factor = 2.01;
        const double time = 2.0 + 0.5 * (u(rng) + 1.0) / 2.0;
        traced.object_bounds(time, all);
        traced.object_bounds_near(axis, half_angle, factor, time, 10.0, near);
        // What near returns are exactly object_bounds' entries, in order.
        std::size_t j = 0;
        for (const raytrace::ObjectBounds& b : all) {
            const Eigen::Vector3d to = b.centre_world - sensor;
            const bool meets = to.norm() <= b.radius_m ||
                               std::acos(std::clamp(axis.dot(to.normalized()), -1.0, 1.0)) <=
                                   half_angle + factor * std::asin(b.radius_m / to.norm());
            const bool listed = j < near.size() && near[j].object_id == b.object_id;
            if (meets) {
                ++met;
                REQUIRE(listed);
            }
            if (!listed) {
                ++culled;
                continue;
            }
            CHECK(near[j].centre_world == b.centre_world);
            CHECK(near[j].world_from_model == b.world_from_model);
            ++j;
        }
        CHECK(j == near.size());
        // Static meshes wider than a given angle are left out: here every static one.
        traced.object_bounds_near(axis, half_angle, factor, time, 0.0, near);
        for (const raytrace::ObjectBounds& b : near) CHECK(b.moving);
    }
    CHECK(met > 100);          // the cones met objects often enough to test something
    CHECK(culled > 4000 * 30);  // and most objects, most of the time, were never placed
}
