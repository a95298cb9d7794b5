#include "ladarsim/sensor_model/render/geometry_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <optional>

#include "ladarsim/sensor_model/sensor/beam_geometry.h"
#include "ladarsim/sensor_model/sensor/gimbal.h"
#include "ladarsim/core/units.h"

namespace ladarsim::sensor_model {

namespace {


std::string object_label(const scene::SceneObject& o) {
    return "object " + std::to_string(o.id) + " (" + std::string(scene::to_string(o.object_class)) +
           (o.name.empty() ? "" : " " + o.name) + ")";
}

std::string fixed(double value, int decimals) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

/// "in frame 3" or "in frames 3 to 39 (37 of 40)".
std::string frames_text(int first, int count, int frames) {
    if (count == 1) return "in frame " + std::to_string(first);
    return "from frame " + std::to_string(first) + " (" + std::to_string(count) + " of " + std::to_string(frames) + " frames)";
}

/// Counts the frames for which `test(k)` holds and remembers the first.
template <class Test>
std::pair<int, int> first_and_count(int frames, Test test) {
    int first = -1, count = 0;
    for (int k = 0; k < frames; ++k) {
        if (!test(k)) continue;
        if (first < 0) first = k;
        ++count;
    }
    return {first, count};
}

}  // namespace

std::vector<std::string> geometry_warnings(const Scenario& scenario, FrameRenderer& renderer, int frames) {
    std::vector<std::string> warnings;
    const Receiver& receiver = scenario.sensor.receiver;
    auto time_of = [&](int k) { return renderer.frame_start_s(static_cast<std::uint64_t>(k)); };
    // Where the sensor is as frame k starts (a moving platform's pose changes frame by frame).
    auto pose_of = [&](int k) { return scenario.mount.world_from_sensor(time_of(k)); };

    // The sensor inside an object: its beams meet surfaces right at the sensor. Every beam's axis
    // at the first, middle and last frame's pointing is traced; a hit closer than the receiver's
    // minimum range (or 0.1 m without one) cannot be what the user meant.
    const double too_close_m = receiver.min_range_m > 0.0 ? receiver.min_range_m : 0.1;
    const ScanPattern& scan = renderer.raster();
    for (const int k : {0, frames / 2, frames - 1}) {
        if (k < 0) continue;
        const Eigen::Isometry3d world_from_sensor_k = pose_of(k);
        const Eigen::Vector3d sensor = world_from_sensor_k.translation();
        const Eigen::Matrix3d world_from_sensor = world_from_sensor_k.linear();
        const GimbalPointing pointing = renderer.gimbal_pointing(static_cast<std::uint64_t>(k));
        std::vector<raytrace::Ray> rays;
        for (int row = 0; row < scan.rows(); ++row) {
            for (int step = 0; step < scan.columns(); ++step) {
                const RasterBeam beam = scan.beam(row, step);
                raytrace::Ray ray;
                ray.origin_world = sensor;
                ray.direction = world_from_sensor * sensor_from_beam(pointing, beam.az_offset_rad, beam.el_offset_rad) *
                                Eigen::Vector3d::UnitX();
                ray.time_s = time_of(k) + beam.time_offset_s;
                ray.max_range_m = too_close_m;
                rays.push_back(ray);
            }
        }
        std::vector<std::optional<raytrace::Hit>> hits(rays.size());
        renderer.traced().trace(rays, hits);
        std::map<std::uint32_t, std::pair<int, double>> close;  // object -> beams, nearest range
        for (const auto& h : hits) {
            if (!h || h->range_m >= too_close_m) continue;
            auto& [beams, nearest] = close.try_emplace(h->object_id, 0, h->range_m).first->second;
            ++beams;
            nearest = std::min(nearest, h->range_m);
        }
        if (close.empty()) continue;
        for (const auto& [id, found] : close) {
            std::string label = "object " + std::to_string(id);
            for (const auto& o : scenario.scene.objects)
                if (o.id == id) label = object_label(o);
            if (id == 0) label = "the background map";
            warnings.push_back("the sensor at (" + fixed(sensor.x(), 2) + ", " + fixed(sensor.y(), 2) + ", " + fixed(sensor.z(), 2) +
                               ") m looks like it is inside " + label + ": in frame " + std::to_string(k) + ", " +
                               std::to_string(found.first) + " of " + std::to_string(rays.size()) + " beams meet it " +
                               fixed(found.second * 1000.0, 2) + " mm away, closer than the receiver's minimum range (" +
                               (receiver.min_range_m > 0.0 ? "min_range_m " + fixed(receiver.min_range_m, 2) + " m), so they return nothing"
                                                           : "none set: min_range_m), so they return from millimetres") +
                               "; move the sensor or the object");
        }
        break;  // once
    }
    // Deeper inside, its walls beyond the minimum range: the six rays along the world's axes all
    // meet the same object (a building's walls, floor and roof), which returns from within.
    if (warnings.empty()) {
        const Eigen::Vector3d sensor = pose_of(0).translation();
        std::vector<raytrace::Ray> axes;
        for (int axis = 0; axis < 6; ++axis) {
            raytrace::Ray ray;
            ray.origin_world = sensor;
            ray.direction = Eigen::Vector3d::Unit(axis / 2) * (axis % 2 ? -1.0 : 1.0);
            ray.time_s = time_of(0);
            ray.max_range_m = receiver.max_range_m;
            axes.push_back(ray);
        }
        std::vector<std::optional<raytrace::Hit>> hits(axes.size());
        renderer.traced().trace(axes, hits);
        const bool enclosed = std::all_of(hits.begin(), hits.end(), [&](const std::optional<raytrace::Hit>& h) {
            return h && h->object_id != 0 && h->object_id == hits[0]->object_id;
        });
        if (enclosed) {
            double farthest_m = 0.0;
            for (const auto& h : hits) farthest_m = std::max(farthest_m, h->range_m);
            std::string label = "object " + std::to_string(hits[0]->object_id);
            for (const auto& o : scenario.scene.objects)
                if (o.id == hits[0]->object_id) label = object_label(o);
            warnings.push_back("the sensor at (" + fixed(sensor.x(), 2) + ", " + fixed(sensor.y(), 2) + ", " + fixed(sensor.z(), 2) +
                               ") m looks like it is inside " + label + ": it meets it in all six directions (up, down, " +
                               "north, south, east, west) within " + fixed(farthest_m, 1) +
                               " m, and its beams will return from its inside walls; move the sensor or the object");
        }
    }

    const GimbalLimits& limits = scenario.sensor.gimbal;
    const bool fixed_head = limits.az_limit_deg == 0.0 && limits.el_min_deg == 0.0 && limits.el_max_deg == 0.0;
    for (const auto& o : scenario.scene.objects) {
        if (o.id != scenario.mount.cue_object_id || fixed_head) continue;
        const Gimbal gimbal(limits, GimbalPointing{});
        GimbalPointing wanted{};
        const auto [first, count] = first_and_count(frames, [&](int k) {
            const GimbalPointing cue = pointing_towards(pose_of(k).inverse() * object_centre_world(o, time_of(k)));
            const GimbalPointing reachable = gimbal.clamp(cue);
            const bool out = std::abs(reachable.az_rad - cue.az_rad) > 1e-9 || std::abs(reachable.el_rad - cue.el_rad) > 1e-9;
            if (out && wanted.az_rad == 0.0 && wanted.el_rad == 0.0) wanted = cue;
            return out;
        });
        if (count == 0) continue;
        warnings.push_back("the cue, " + object_label(o) + ", is at azimuth " + fixed(wanted.az_rad / kDeg, 1) +
                           " deg, elevation " + fixed(wanted.el_rad / kDeg, 1) + " deg " + frames_text(first, count, frames) +
                           ", beyond the gimbal's reach (azimuth +-" + fixed(limits.az_limit_deg, 0) + " deg, elevation " +
                           fixed(limits.el_min_deg, 0) + " to " + fixed(limits.el_max_deg, 0) +
                           " deg): the gimbal parks at its limit and the field misses it");
    }

    for (const auto& o : scenario.scene.objects) {
        const bool of_interest = scenario.mount.cue_object_id != 0 ? o.id == scenario.mount.cue_object_id
                                                                   : o.object_class == scene::ObjectClass::drone;
        if (!of_interest) continue;
        double range_m = 0.0;
        const auto [first, count] = first_and_count(frames, [&](int k) {
            const double r = (object_centre_world(o, time_of(k)) - pose_of(k).translation()).norm();
            if (r > receiver.max_range_m && range_m == 0.0) range_m = r;
            return r > receiver.max_range_m;
        });
        if (count == 0) continue;
        warnings.push_back(object_label(o) + " is " + fixed(range_m, 0) + " m away " + frames_text(first, count, frames) +
                           ", beyond the receiver's max_range_m of " + fixed(receiver.max_range_m, 0) + " m: it returns nothing");
    }
    return warnings;
}

}  // namespace ladarsim::sensor_model
