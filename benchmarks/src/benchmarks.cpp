#include "ladarsim/bench/benchmarks.h"

#include <algorithm>
#include <cmath>

#include <tbb/global_control.h>

#include "bench_frames.h"
#include "hard_cases.h"
#include "peer.h"
#include "scaling.h"
#include "ladarsim/raytrace/traced_scene.h"
#include "ladarsim/sensor_model/render/frame_renderer.h"

namespace ladarsim::bench {

namespace {

using nlohmann::json;
using sensor_model::Scenario;

constexpr int kReferenceSamples = 4096;  ///< sub-rays per beam of the converged reference

std::vector<std::uint64_t> every(std::uint64_t step, std::uint64_t count) {
    std::vector<std::uint64_t> v;
    for (std::uint64_t i = 0; i < count; i += step) v.push_back(i);
    return v;
}

/// One footprint integration: `samples` > 0 fixed sub-rays per beam, else adaptive at `tolerance`.
struct Setting {
    int samples;
    double tolerance;
    std::string label() const { return samples ? std::to_string(samples) + " sub-rays" : "tolerance " + std::to_string(tolerance); }
};

/// The settings the real-time and recorded-map benchmarks sweep.
const std::vector<Setting> kSweep = {{0, 0.2}, {0, 0.05}, {0, 0.01}, {16, 0.0}, {64, 0.0}};

/// A setting's speed: the fields every benchmark row starts with.
json speed(const Setting& s, const Rendering& r, const Scenario& scenario) {
    return {{"footprint_samples", s.samples},
            {"footprint_tolerance", s.tolerance},
            {"beams_per_s", r.beams_per_second()},
            {"rays_per_beam", r.rays_per_beam()},
            {"realtime_factor", scenario.sensor.realtime_factor(r.beams_per_second())}};
}

/// Our render of one frame against Embree's traversal alone of the very rays it traced, in the
/// same batches on the same scene, on one thread each (a ratio of work, not of scheduling: both
/// are timed in the thread's own CPU time, which other processes on a shared machine do not
/// lengthen, the best of five).
json pipeline_against_raw(const Scenario& scenario, std::uint64_t frame) {
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    sensor_model::FrameRenderer renderer(scenario);
    std::vector<std::vector<raytrace::Ray>> batches;
    renderer.traced().record_rays(&batches);
    renderer.render(frame);
    renderer.traced().record_rays(nullptr);
    const std::uint64_t rays = renderer.rays_last_frame();
    double pipeline_s = 1e300, raw_s = 1e300;
    std::size_t hits = 0;
    for (int repeat = 0; repeat < 5; ++repeat) {
        double start = thread_cpu_seconds();
        renderer.render(frame);
        pipeline_s = std::min(pipeline_s, thread_cpu_seconds() - start);
        hits = 0;
        start = thread_cpu_seconds();
        for (const auto& b : batches) hits += renderer.traced().intersect_only(b);
        raw_s = std::min(raw_s, thread_cpu_seconds() - start);
    }
    return {{"frame", frame},
            {"rays", rays},
            {"hits", hits},
            {"batches", batches.size()},
            {"pipeline_rays_per_s", rays / pipeline_s},
            {"raw_embree_rays_per_s", rays / raw_s},
            // The ratio below falls when the pipeline traces fewer rays for the same frame: the
            // frame's own time says what it costs.
            {"pipeline_frame_ms", 1e3 * pipeline_s},
            {"raw_embree_frame_ms", 1e3 * raw_s},
            {"pipeline_vs_raw_embree", raw_s / pipeline_s}};
}

/// The scenario as shipped, at each accuracy setting: real-time factor and point counts against
/// the converged reference (noise off, so that counts are expectations, not draws).
json realtime(const Scenario& scenario, const BenchOptions& options) {
    const std::uint64_t frames = static_cast<std::uint64_t>(scenario.render.frames);
    const std::vector<std::uint64_t> indices = every(options.quick ? std::max<std::uint64_t>(1, frames / 30) : 1, frames);
    const std::vector<std::uint64_t> checked = every(std::max<std::uint64_t>(1, frames / (options.quick ? 10 : 30)), frames);
    const std::uint32_t target = scenario.mount.cue_object_id;
    Scenario quiet = scenario;
    quiet.render.noise = false;
    options.progress("real time: converged reference (" + std::to_string(kReferenceSamples) + " sub-rays per beam, " +
                     std::to_string(checked.size()) + " frames)");
    const Scenario reference_scenario = with_footprint(quiet, kReferenceSamples, 0.0);
    const Rendering reference = render_frames(reference_scenario, checked);

    json settings = json::array();
    for (const Setting& s : kSweep) {
        options.progress("real time: " + s.label());
        const Scenario timed_scenario = with_footprint(scenario, s.samples, s.tolerance);
        const Rendering timed = render_frames(timed_scenario, indices);
        const Scenario checked_scenario = with_footprint(quiet, s.samples, s.tolerance);
        const Rendering counted = render_frames(checked_scenario, checked);
        const ObjectError e = compare(counted, reference, target);
        std::uint64_t all = 0, all_reference = 0;
        for (const auto& f : counted.frames) all += f.returns.size();
        for (const auto& f : reference.frames) all_reference += f.returns.size();
        json row = speed(s, timed, scenario);
        row.update({{"target_returns", e.returns},
                    {"reference_target_returns", e.reference_returns},
                    {"count_error_pct", e.count_error_pct},
                    {"energy_error_pct", e.energy_error_pct},
                    {"range_error_mm", e.range_error_mm},
                    {"all_returns_error_pct", 100.0 * (double(all) - double(all_reference)) / double(all_reference)}});
        settings.push_back(row);
    }
    return {{"scenario", scenario.file.string()},
            {"frames_timed", indices.size()},
            {"frames_checked", checked.size()},
            {"reference_samples", kReferenceSamples},
            {"sensor_beams_per_s", scenario.sensor.rated_beams_per_second()},
            {"settings", settings}};
}

/// A 0.3 m drone held at 200, 1000 and 2000 m along the scenario's approach, in front of its
/// terrain: beams/s against the error of its returns, adaptive tolerances and fixed counts.
json accuracy(const Scenario& scenario, const BenchOptions& options) {
    const std::uint32_t target = scenario.mount.cue_object_id;
    const std::vector<std::uint64_t> indices = every(1, options.quick ? 3 : 10);
    json curves = json::array();
    for (const double distance : {200.0, 1000.0, 2000.0}) {
        Scenario held = scenario;
        held.render.noise = false;
        for (auto& object : held.scene.objects) {
            if (object.id != target) continue;
            const scene::Pose start = object.trajectory.at(0.0);
            const Eigen::Vector3d towards = (start.position - scenario.mount.position_world).normalized();
            object.trajectory = scene::Trajectory::fixed(
                scene::Pose{scenario.mount.position_world + distance * towards, start.orientation});
        }
        options.progress("accuracy at " + std::to_string(int(distance)) + " m: reference");
        const Scenario reference_scenario = with_footprint(held, kReferenceSamples, 0.0);
        const Rendering reference = render_frames(reference_scenario, indices);
        json points = json::array();
        for (const Setting s : {Setting{0, 0.3}, Setting{0, 0.1}, Setting{0, 0.05}, Setting{0, 0.02}, Setting{0, 0.01},
                                Setting{1, 0}, Setting{4, 0}, Setting{16, 0}, Setting{64, 0}, Setting{256, 0},
                                Setting{1024, 0}}) {
            const Scenario setting_scenario = with_footprint(held, s.samples, s.tolerance);
            const Rendering r = render_frames(setting_scenario, indices);
            const ObjectError e = compare(r, reference, target);
            points.push_back({{"method", s.samples ? "fixed" : "adaptive"},
                              {"footprint_samples", s.samples},
                              {"footprint_tolerance", s.tolerance},
                              {"beams_per_s", r.beams_per_second()},
                              {"rays_per_beam", r.rays_per_beam()},
                              {"target_returns", e.returns},
                              {"reference_target_returns", e.reference_returns},
                              {"count_error_pct", e.count_error_pct},
                              {"energy_error_pct", e.energy_error_pct},
                              {"range_error_mm", e.range_error_mm}});
        }
        curves.push_back({{"distance_m", distance}, {"frames", indices.size()}, {"points", points}});
    }
    return {{"reference_samples", kReferenceSamples}, {"curves", curves}};
}

/// Frames over a recorded map at each accuracy setting: beams/s and rays per beam against the
/// errors of the map's returns (count, summed intensity, range) and of the target's, all against
/// the converged reference, noise off.
json recorded_map(const BenchOptions& options) {
    Scenario scenario;
    try {
        scenario = sensor_model::load_scenario(options.map_scenario);
    } catch (const std::exception& e) {
        return {{"scenario", options.map_scenario.string()}, {"skipped", e.what()}};
    }
    scenario.render.noise = false;
    const std::uint64_t frames = static_cast<std::uint64_t>(scenario.render.frames);
    const std::vector<std::uint64_t> indices = every(frames / (options.quick ? 2 : 6), frames);
    options.progress("recorded map: converged reference (a scanline of " + std::to_string(kMapReferenceLines) + " lines per beam, " +
                     std::to_string(indices.size()) + " frames)");
    const Rendering reference = render_frames(with_map_reference(scenario, kReferenceSamples, kMapReferenceLines), indices);
    json settings = json::array();
    for (const Setting& s : kSweep) {
        options.progress("recorded map: " + s.label());
        const Rendering r = render_frames(with_footprint(scenario, s.samples, s.tolerance), indices);
        const ObjectError map = compare(r, reference, scene::kBackgroundObjectId);
        const ObjectError target = compare(r, reference, scenario.mount.cue_object_id);
        json row = speed(s, r, scenario);
        row.update({{"map_returns", map.returns},
                    {"reference_map_returns", map.reference_returns},
                    {"map_count_error_pct", map.count_error_pct},
                    {"map_energy_error_pct", map.energy_error_pct},
                    {"map_range_error_mm", map.range_error_mm},
                    {"target_count_error_pct", target.count_error_pct},
                    {"target_energy_error_pct", target.energy_error_pct}});
        settings.push_back(row);
    }
    return {{"scenario", options.map_scenario.string()},
            {"frames", indices.size()},
            {"reference_lines", kMapReferenceLines},
            {"settings", settings}};
}

}  // namespace

nlohmann::json run_benchmarks(const BenchOptions& options) {
    const Scenario scenario = sensor_model::load_scenario(options.scenario);
    json result;
    if (!options.hard_case.empty()) {
        result["hard_cases"] = hard_cases(scenario, options, options.hard_case);
        result["quick"] = options.quick;
        return result;
    }
    options.progress("pipeline against raw Embree");
    result["pipeline"] = pipeline_against_raw(scenario, static_cast<std::uint64_t>(scenario.render.frames / 2));
    result["realtime"] = realtime(scenario, options);
    result["accuracy"] = accuracy(scenario, options);
    result["recorded_map"] = recorded_map(options);
    result["scaling"] = scaling(scenario, options);
    result["hard_cases"] = hard_cases(scenario, options);
    result["peer"] = peer_scene(scenario, options);
    result["pipeline_vs_raw_embree"] = result["pipeline"]["pipeline_vs_raw_embree"];
    // The shipped accuracy: the scenario's own footprint setting is the adaptive default.
    for (const json& s : result["realtime"]["settings"]) {
        if (s["footprint_samples"] == 0 && s["footprint_tolerance"] == scenario.render.footprint_tolerance) {
            result["realtime_factor"] = s["realtime_factor"];
            result["count_error_pct"] = s["count_error_pct"];
        }
    }
    result["quick"] = options.quick;
    return result;
}

}  // namespace ladarsim::bench
