#include "ladarsim/sensor_model/dataset.h"

#include <chrono>
#include <filesystem>

#include <spdlog/spdlog.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include "ladarsim/scene/input_error.h"
#include "ladarsim/sensor_model/frame_io.h"
#include "ladarsim/sensor_model/frame_renderer.h"

namespace ladarsim::sensor_model {

namespace {

nlohmann::json mount_json(const SensorMount& m) {
    nlohmann::json j = {
        {"position_m", {m.position_world.x(), m.position_world.y(), m.position_world.z()}},
        {"orientation_wxyz", {m.orientation.w(), m.orientation.x(), m.orientation.y(), m.orientation.z()}},
        {"cue_object", m.cue_object_id},
    };
    if (m.gimbal_az_deg) j["gimbal_az_deg"] = *m.gimbal_az_deg;
    if (m.gimbal_el_deg) j["gimbal_el_deg"] = *m.gimbal_el_deg;
    return j;
}

nlohmann::json render_json(const RenderSettings& r) {
    return {{"frames", r.frames},
            {"seed", r.seed},
            {"start_time_s", r.start_time_s},
            {"motion_steps", r.motion_steps},
            {"jitter", r.jitter}};
}

/// The output directory as an absolute path without a trailing separator, checked before any
/// rendering: it may be absent, empty, or a previous ladarsim dataset (which is replaced), but
/// never some other directory a user would lose.
std::filesystem::path checked_out_dir(const std::filesystem::path& requested) {
    std::filesystem::path out = std::filesystem::absolute(requested).lexically_normal();
    if (!out.has_filename()) out = out.parent_path();
    std::error_code ec;
    if (!std::filesystem::exists(out, ec)) return out;
    if (!std::filesystem::is_directory(out, ec)) throw InputError(out.string(), "--out", "exists and is not a directory");
    if (!std::filesystem::is_empty(out, ec) && !std::filesystem::exists(out / "manifest.json", ec))
        throw InputError(out.string(), "--out",
                         "is a non-empty directory without a ladarsim manifest.json; refusing to replace it");
    return out;
}

/// Moves the finished staging directory to `out`, replacing a previous dataset there.
void swap_in(const std::filesystem::path& staging, const std::filesystem::path& out) {
    const std::filesystem::path old = out.string() + ".old";
    std::filesystem::remove_all(old);
    if (std::filesystem::exists(out)) std::filesystem::rename(out, old);
    std::filesystem::rename(staging, out);
    std::filesystem::remove_all(old);
}

}  // namespace

DatasetSummary render_dataset(Scenario scenario, const DatasetOptions& options) {
    if (options.frames) scenario.render.frames = *options.frames;
    if (options.seed) scenario.render.seed = *options.seed;
    const int threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
    tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));

    // Built beside the destination and swapped in when complete: an interrupted run leaves a
    // previous dataset untouched, and a finished one never mixes with its stale frames.
    const std::filesystem::path out = checked_out_dir(options.out_dir);
    const std::filesystem::path staging = out.string() + ".partial";
    std::filesystem::remove_all(staging);
    const std::filesystem::path frames_dir = staging / "frames";
    std::filesystem::create_directories(frames_dir);

    FrameRenderer renderer(scenario);
    DatasetSummary summary;
    summary.out_dir = out;
    std::vector<FrameGroundTruth> truth;
    nlohmann::json frame_log = nlohmann::json::array();
    using Clock = std::chrono::steady_clock;

    for (int k = 0; k < scenario.render.frames; ++k) {
        const auto started = Clock::now();
        const Frame frame = renderer.render(static_cast<std::uint64_t>(k));
        const double seconds = std::chrono::duration<double>(Clock::now() - started).count();
        summary.render_seconds += seconds;

        const std::string stem = frame_file_stem(frame.index);
        write_frame_pcd(frames_dir / (stem + ".pcd"), frame);
        write_frame_exr(frames_dir / (stem + ".exr"), frame);

        summary.returns += frame.returns.size();
        for (const auto& r : frame.returns) ++summary.returns_by_object[r.object_id];
        truth.push_back(ground_truth_of(frame));
        frame_log.push_back({{"index", frame.index},
                             {"start_time_s", frame.start_time_s},
                             {"end_time_s", frame.end_time_s},
                             {"gimbal_az_rad", frame.gimbal_az_rad},
                             {"gimbal_el_rad", frame.gimbal_el_rad},
                             {"returns", frame.returns.size()},
                             {"render_s", seconds}});
        if (options.progress) options.progress(k + 1, scenario.render.frames);
    }
    summary.frames = scenario.render.frames;
    summary.beams_per_second =
        summary.render_seconds > 0.0
            ? double(renderer.raster().beam_count()) * summary.frames / summary.render_seconds
            : 0.0;

    write_ground_truth_json(staging / "ground_truth.json", truth);
    const nlohmann::json manifest = {
        {"software", {{"name", "ladarsim"}, {"version", LADARSIM_VERSION}}},
        {"scenario_file", std::filesystem::absolute(scenario.file).string()},
        {"scenario", scenario.source},
        {"sensor", to_json(scenario.sensor)},
        {"mount", mount_json(scenario.mount)},
        {"render", render_json(scenario.render)},
        {"threads", threads},
        {"frames", frame_log},
        {"totals",
         {{"frames", summary.frames},
          {"returns", summary.returns},
          {"render_s", summary.render_seconds},
          {"beams_per_s", summary.beams_per_second}}},
    };
    write_json(staging / "manifest.json", manifest);
    swap_in(staging, out);
    return summary;
}

}  // namespace ladarsim::sensor_model
