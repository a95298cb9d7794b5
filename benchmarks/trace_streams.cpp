// How much does TracedScene cost over raw Embree on the same rays, and what does its double-precision
// range refinement change? Prints ratios measured in one run (machines are noisy; ratios are not).
//
// Scene: the shipped procedural terrain and quadcopter. Rays: one frame of the paper's raster
// (150 x 20 beams, 16 sub-rays each) from a sensor 3 m above the ground, aimed (a) at the drone
// 600 m away, (b) 2 degrees down at the terrain, (c) above the horizon (all misses).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include <embree3/rtcore.h>

#include "ladarsim/raytrace/traced_scene.h"
#include "ladarsim/scene/procedural_models.h"
#include "ladarsim/sensor_model/footprint/footprint.h"
#include "ladarsim/sensor_model/sensor/sensor.h"
#include "ladarsim/core/units.h"

using namespace ladarsim;
using Clock = std::chrono::steady_clock;

namespace {

const Eigen::Vector3d kSensor(0.0, 0.0, 3.0);

scene::Scene benchmark_scene() {
    scene::Scene s;
    scene::SceneObject terrain;
    terrain.id = 1;
    terrain.object_class = scene::ObjectClass::terrain;
    terrain.model = std::make_shared<scene::Model>(scene::make_terrain());
    terrain.trajectory = scene::Trajectory::fixed(scene::Pose{});
    scene::SceneObject drone;
    drone.id = 2;
    drone.model = std::make_shared<scene::Model>(scene::make_quadcopter());
    drone.trajectory = scene::Trajectory::fixed(scene::Pose{{600.0, 0.0, 3.0}, Eigen::Quaterniond::Identity()});
    s.objects = {terrain, drone};
    return s;
}

/// Rays of one frame, sub-ray by sub-ray, around a boresight `elevation_deg` above the horizon.
std::vector<raytrace::Ray> frame_rays(double elevation_deg) {
    const sensor_model::Sensor sensor = sensor_model::sensor_preset("paper_ladar");
    const sensor_model::ScanPattern& raster = *sensor.scan;
    const sensor_model::Footprint footprint(sensor.transmitter.divergence_mrad * kMrad, 16, 1.5);
    std::vector<sensor_model::SubRay> sub(16);
    footprint.fixed(sub);
    std::vector<raytrace::Ray> rays;
    const double el0 = elevation_deg * M_PI / 180.0;
    for (int b = 0; b < raster.beam_count(); ++b) {
        const sensor_model::RasterBeam beam = raster.beam(b / raster.columns(), b % raster.columns());
        for (const auto& s : sub) {
            const double az = beam.az_offset_rad + s.offset_x_rad, el = el0 + beam.el_offset_rad + s.offset_y_rad;
            raytrace::Ray r;
            r.origin_world = kSensor;
            r.direction = Eigen::Vector3d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
            r.time_s = beam.time_offset_s;
            rays.push_back(r);
        }
    }
    return rays;
}

/// The same triangles handed straight to Embree, as TracedScene places static meshes.
struct RawEmbree {
    RTCDevice device = rtcNewDevice(nullptr);
    RTCScene scene = rtcNewScene(device);

    explicit RawEmbree(const scene::Scene& s) {
        for (const auto& object : s.objects) {
            const auto& mesh = object.model->mesh;
            Eigen::Isometry3d pose = object.trajectory.at(0.0).world_from_object();
            pose.translation() -= kSensor;
            RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
            auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                  3 * sizeof(float), mesh.positions.size()));
            auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                     3 * sizeof(unsigned), mesh.triangles.size()));
            for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
                const Eigen::Vector3d p = pose * (object.scale * mesh.positions[i].cast<double>());
                for (int k = 0; k < 3; ++k) v[3 * i + k] = static_cast<float>(p[k]);
            }
            for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
                for (int k = 0; k < 3; ++k) t[3 * i + k] = mesh.triangles[i][k];
            rtcCommitGeometry(g);
            rtcAttachGeometry(scene, g);
            rtcReleaseGeometry(g);
        }
        rtcCommitScene(scene);
    }
    ~RawEmbree() {
        rtcReleaseScene(scene);
        rtcReleaseDevice(device);
    }

    void trace(const std::vector<raytrace::Ray>& rays, std::vector<RTCRayHit>& out) const {
        out.resize(rays.size());
        for (std::size_t i = 0; i < rays.size(); ++i) {
            RTCRayHit& rh = out[i];
            rh = RTCRayHit{};
            const Eigen::Vector3f d = rays[i].direction.cast<float>();
            rh.ray.dir_x = d.x();
            rh.ray.dir_y = d.y();
            rh.ray.dir_z = d.z();
            rh.ray.tfar = static_cast<float>(rays[i].max_range_m);
            rh.ray.mask = 0xFFFFFFFFu;
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        }
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        rtcIntersect1M(scene, &context, out.data(), static_cast<unsigned>(out.size()), sizeof(RTCRayHit));
    }
};

template <typename F>
double best_seconds(int repeats, F&& f) {
    double best = 1e30;
    for (int i = 0; i < repeats; ++i) {
        const auto t0 = Clock::now();
        f();
        best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
    }
    return best;
}

}  // namespace

int main() {
    const scene::Scene s = benchmark_scene();
    const raytrace::TracedScene traced(s, kSensor);
    const RawEmbree raw(s);
    std::printf("%-30s %9s %8s %12s %12s %12s %14s\n", "view", "rays", "hits", "raw Mray/s", "stream/raw", "single/raw",
                "max |dR| mm");
    const struct { const char* name; double elevation_deg; } views[] = {
        {"drone at 600 m, ridge behind", 0.0}, {"terrain, 2 deg down", -2.0}, {"sky (all misses)", 5.0}};
    const int repeats = 7;
    for (const auto& view : views) {
        const std::vector<raytrace::Ray> rays = frame_rays(view.elevation_deg);
        std::vector<RTCRayHit> raw_hits;
        std::vector<std::optional<raytrace::Hit>> hits(rays.size());
        const double t_raw = best_seconds(repeats, [&] { raw.trace(rays, raw_hits); });
        const double t_stream = best_seconds(repeats, [&] { traced.trace(rays, hits); });
        const double t_single = best_seconds(repeats, [&] {
            for (std::size_t i = 0; i < rays.size(); ++i) hits[i] = traced.trace(rays[i]);
        });
        // What the double-precision refinement changes relative to Embree's float distance.
        std::size_t n_hits = 0;
        double max_change_mm = 0.0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            if (!hits[i]) continue;
            ++n_hits;
            if (raw_hits[i].hit.geomID != RTC_INVALID_GEOMETRY_ID)
                max_change_mm = std::max(max_change_mm, 1e3 * std::abs(hits[i]->range_m - raw_hits[i].ray.tfar));
        }
        std::printf("%-30s %9zu %8zu %12.2f %12.2f %12.2f %14.3f\n", view.name, rays.size(), n_hits,
                    rays.size() / t_raw / 1e6, t_stream / t_raw, t_single / t_raw, max_change_mm);
    }
    std::printf("stream/raw and single/raw: time of TracedScene (Embree plus our hit records and double-precision\n"
                "ranges) over raw Embree rtcIntersect1M on the same rays and triangles; best of %d runs each.\n",
                repeats);
    return 0;
}
