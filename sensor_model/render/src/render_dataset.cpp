#include "ladarsim/sensor_model/render/render_dataset.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

#include <spdlog/spdlog.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include "ladarsim/dataset/dataset_directory.h"
#include "ladarsim/dataset/frame_io.h"
#include "ladarsim/dataset/ground_truth_file.h"
#include "ladarsim/dataset/manifest.h"
#include "ladarsim/dataset/poses_file.h"
#include "ladarsim/core/input_error.h"
#include "ladarsim/core/json_file.h"
#include "ladarsim/sensor_model/render/frame_renderer.h"
#include "ladarsim/sensor_model/render/geometry_checks.h"
#include "frame_writer.h"
#include "frames_at_once.h"
#include "initial_map_survey.h"

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
    // Only on a moving platform (a fixed mount keeps the manifest it always had): position_m is
    // then where the platform started and orientation_wxyz the mount's on it; the poses are in
    // poses.txt and sensor_trajectory.txt.
    if (m.moves()) j["moving_platform"] = true;
    return j;
}

/// Samples of a moving sensor's pose for motion compensation: every millisecond of each frame's
/// scan, and its end. Linear and slerp interpolation between them (pose_at) is then within
/// (2 pi f)^2 A dt^2 / 8 of the truth for a sway of amplitude A at frequency f: 0.2 microradians
/// for 2 degrees at 1 Hz.
constexpr double kTrajectorySample_s = 1e-3;

std::vector<TimedPose> sensor_trajectory(const Scenario& scenario, const FrameRenderer& renderer, int frames) {
    std::vector<TimedPose> poses;
    const double scan_s = renderer.raster().frame_scan_duration_s();
    const int steps = std::max(1, static_cast<int>(std::ceil(scan_s / kTrajectorySample_s)));
    for (int k = 0; k < frames; ++k) {
        const double start = renderer.frame_start_s(static_cast<std::uint64_t>(k));
        for (int i = 0; i <= steps; ++i) {
            const double t = i == steps ? start + scan_s : start + i * kTrajectorySample_s;
            if (!poses.empty() && !(t > poses.back().time_s)) continue;  // a frame that starts as the last ends
            poses.push_back({t, scenario.mount.world_from_sensor(t)});
        }
    }
    return poses;
}

nlohmann::json render_json(const RenderSettings& r) {
    nlohmann::json j = {{"frames", r.frames},
                        {"seed", r.seed},
                        {"start_time_s", r.start_time_s},
                        {"motion_steps", r.motion_steps},
                        {"jitter", r.jitter},
                        {"noise", r.noise},
                        {"footprint_samples", r.footprint_samples},
                        {"footprint_tolerance", r.footprint_tolerance},
                        {"footprint_truncation", r.footprint_truncation}};
    // Only when on: a render without waveforms keeps the manifest it always had.
    if (r.waveforms) j["waveforms"] = true;
    return j;
}

/// Locks the staging directory and starts it afresh, or (with `resume`) keeps what an interrupted
/// run of the same scenario, seed and frame count left there.
void prepare_staging(const std::filesystem::path& out, const StagingFiles& files, const nlohmann::json& run_key, bool resume,
                     std::optional<StagingDir>& staging_lock) {
    staging_lock.emplace(out);
    const bool interrupted = std::filesystem::exists(files.run_file);
    if (interrupted && !resume)
        throw InputError(out.string(), "--out",
                         files.staging.filename().string() + " holds the finished frames of an interrupted render: continue it "
                         "with --resume, or delete " + files.staging.string() + " to start over");
    if (resume && !interrupted) spdlog::warn("--resume: {} holds no interrupted render; rendering from the start", files.staging.string());
    if (interrupted && read_json(files.run_file) != run_key)
        throw InputError(files.run_file.string(), "run",
                         "the interrupted run is of another scenario, seed or frame count; delete " + files.staging.string() +
                             " to start over");
    if (!interrupted) {
        staging_lock->clear();
        std::filesystem::create_directories(files.frames_dir);
        write_json(files.run_file, run_key);
    }
}

/// The frames below `frames` whose records are in the staging directory, in order. From the
/// directory, not frame by frame: after Ctrl-C early in a run of millions of frames, asking for
/// each would take seconds.
std::vector<int> finished_frames(const StagingFiles& files, int frames) {
    std::vector<int> finished;
    for (const auto& e : std::filesystem::directory_iterator(files.frames_dir)) {
        const std::string name = e.path().filename().string();
        if (name.size() > 9 && name.ends_with(".log.json")) {
            const long long k = std::stoll(name.substr(0, name.size() - 9));
            if (k < frames) finished.push_back(static_cast<int>(k));
        }
    }
    std::sort(finished.begin(), finished.end());
    return finished;
}

/// Starts the initial map's survey: the gimbal's replay over every frame (two angles a frame,
/// checked for Ctrl-C as a run of millions goes) gives the field it needs.
void start_survey(const Scenario& scenario, FrameRenderer& renderer, const std::atomic<bool>* stop, const std::filesystem::path& file,
                  std::optional<InitialMapSurvey>& survey) {
    const auto stopped = [stop] { return stop && stop->load(); };
    PointingExtent looked;
    for (int k = 0; k < scenario.render.frames && !(k % 65536 == 0 && stopped()); ++k)
        looked.add(renderer.gimbal_pointing(static_cast<std::uint64_t>(k)));
    if (!stopped()) survey.emplace(scenario, looked, file);
}

/// What is on disk now, every finished frame's record from whichever process wrote it, into the
/// summary, the manifest's frame log and the ground truth. The writer's own frames come from
/// memory; those of an interrupted run, or of another process, are read back from their files.
void collect_frames(const StagingFiles& files, int frames, FrameWriter& writer, DatasetSummary& summary,
                    std::vector<FrameGroundTruth>& truth, nlohmann::json& frame_log) {
    for (const int k : finished_frames(files, frames)) {
        const auto here = writer.written().find(k);
        FrameRecord finished = here != writer.written().end()
                                   ? std::move(here->second)
                                   : FrameRecord{read_json(files.record_of(k)), read_ground_truth_json(files.truth_of(k)).at(0)};
        nlohmann::json& record = finished.record;
        for (const auto& [id, count] : record.at("returns_by_object").items())
            summary.returns_by_object[static_cast<std::uint32_t>(std::stoul(id))] += count.get<std::uint64_t>();
        record.erase("returns_by_object");
        summary.returns += record.at("returns").get<std::uint64_t>();
        summary.render_seconds += record.at("render_s").get<double>();
        truth.push_back(std::move(finished.truth));
        frame_log.push_back(std::move(record));
    }
    summary.frames = static_cast<int>(frame_log.size());
}

}  // namespace

DatasetSummary render_dataset(Scenario scenario, const DatasetOptions& options) {
    if (options.frames && (*options.frames < 1 || *options.frames > kMaxFrames))
        throw InputError(std::to_string(*options.frames), "frames", "is not a whole number from 1 to " + std::to_string(kMaxFrames));
    if (options.frames) scenario.render.frames = *options.frames;
    if (options.seed) scenario.render.seed = *options.seed;
    const int threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
    tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    FrameTeam alone;
    FrameTeam& team = options.team ? *options.team : alone;
    const bool first_process = team.rank() == 0;

    // Built beside the destination and swapped in when complete: an interrupted run leaves a
    // previous dataset untouched, and a finished one never mixes with its stale frames.
    const std::filesystem::path out = checked_dataset_dir(options.out_dir);
    const StagingFiles files(staging_dir(out));
    const std::filesystem::path& staging = files.staging;
    std::optional<StagingDir> staging_lock;
    const nlohmann::json run_key = {{"scenario", scenario.source}, {"seed", scenario.render.seed}, {"frames", scenario.render.frames}};

    // Frames are independent given the scenario and seed (the gimbal is replayed from frame 0), so
    // the frames an interrupted run left are exactly what this one would render again.
    if (first_process) {
        try {
            prepare_staging(out, files, run_key, options.resume, staging_lock);
        } catch (...) {
            team.any(true);  // the others wait on this before rendering: release them first
            throw;
        }
    }
    if (team.any(false)) throw FrameFailure("the first process could not prepare " + staging.string());

    FrameRenderer renderer(scenario);
    if (first_process)
        for (const std::string& w : geometry_warnings(scenario, renderer, scenario.render.frames))
            spdlog::warn("{}: {}", scenario.file.string(), w);
    std::optional<InitialMapSurvey> survey;
    if (first_process) start_survey(scenario, renderer, options.stop, staging / "background.pcd", survey);
    DatasetSummary summary;
    summary.out_dir = out;
    std::string failure;
    bool stopped = false;
    FrameWriter writer(files, static_cast<std::size_t>(threads));
    // Every process takes the same number of turns, so that the collective checks line up; a
    // batch of frames takes several at once. In a team each process takes one frame a turn:
    // processes may see different numbers of cores, and their batches must still line up.
    const int turns = (scenario.render.frames + team.size() - 1) / team.size();
    FrameBatch batch(scenario, renderer, team.size() == 1 ? frames_at_once(threads, turns) : 1);
    for (int first_turn = 0; first_turn < turns; first_turn += batch.size()) {
        const int end_turn = std::min(first_turn + batch.size(), turns);
        stopped = options.stop && options.stop->load();
        std::vector<int> todo;
        for (int turn = first_turn; turn < end_turn && !stopped; ++turn) {
            const int k = turn * team.size() + team.rank();
            if (k < scenario.render.frames && !std::filesystem::exists(files.record_of(k))) todo.push_back(k);
        }
        for (RenderedFrame& r : batch.render(todo, options.fail_at_frame)) {
            if (failure.empty()) failure = r.failure;
            if (failure.empty()) failure = writer.write(std::move(r.frame), r.render_s, std::move(r.waveforms));
        }
        if (team.any(!failure.empty() || stopped)) break;
        if (options.progress && first_process) options.progress(std::min(end_turn * team.size(), scenario.render.frames), scenario.render.frames);
    }
    if (const std::string written = writer.finish(); failure.empty()) failure = written;
    const bool any_failure = team.any(!failure.empty());
    if (any_failure) {
        // The finished frames stay, and hold their space on the disk: say where, and what to do.
        throw FrameFailure((failure.empty() ? "another process of the run failed" : failure) + "; finished frames are in " +
                           staging.string() + " (continue with --resume, or delete it to free its space)");
    }

    std::vector<FrameGroundTruth> truth;
    nlohmann::json frame_log = nlohmann::json::array();
    collect_frames(files, scenario.render.frames, writer, summary, truth, frame_log);
    summary.beams_per_second =
        summary.render_seconds > 0.0 ? double(renderer.raster().beam_count()) * summary.frames / summary.render_seconds : 0.0;
    if (stopped || summary.frames < scenario.render.frames) {
        summary.interrupted = true;
        return summary;
    }
    if (!first_process) return summary;

    write_ground_truth_json(staging / "ground_truth.json", truth);
    // Each frame's pose at its start (a fixed mount's, every frame the same).
    std::vector<Eigen::Isometry3d> poses;
    for (int k = 0; k < summary.frames; ++k) poses.push_back(scenario.mount.world_from_sensor(renderer.frame_start_s(static_cast<std::uint64_t>(k))));
    write_poses_txt(staging / "poses.txt", poses);
    if (scenario.mount.moves()) write_sensor_trajectory_txt(staging / "sensor_trajectory.txt", sensor_trajectory(scenario, renderer, summary.frames));
    summary.background_points = survey->points();
    write_manifest(staging / "manifest.json",
                   {to_json(scenario.sensor), frame_log,
                    {{"scenario_file", std::filesystem::absolute(scenario.file).string()},
                     {"scenario", scenario.source},
                     {"mount", mount_json(scenario.mount)},
                     {"render", render_json(scenario.render)},
                     {"threads", threads},
                     {"processes", team.size()},
                     {"totals",
                      {{"frames", summary.frames},
                       {"returns", summary.returns},
                       {"render_s", summary.render_seconds},
                       {"beams_per_s", summary.beams_per_second}}}}});
    for (int k = 0; k < scenario.render.frames; ++k) {
        std::filesystem::remove(files.record_of(k));
        std::filesystem::remove(files.truth_of(k));
    }
    std::filesystem::remove(files.run_file);
    summary.kept = swap_in_dataset(staging, out);
    return summary;
}

}  // namespace ladarsim::sensor_model
