#include "ladarsim/sensor_model/render/render_dataset.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <map>
#include <optional>
#include <filesystem>

#include <spdlog/spdlog.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include "ladarsim/dataset/dataset_directory.h"
#include "ladarsim/dataset/frame_io.h"
#include "ladarsim/dataset/ground_truth_file.h"
#include "ladarsim/dataset/manifest.h"
#include "ladarsim/core/input_error.h"
#include "ladarsim/core/json_file.h"
#include "ladarsim/sensor_model/render/frame_renderer.h"
#include "ladarsim/sensor_model/sensor/galvo_raster.h"
#include "ladarsim/sensor_model/render/geometry_checks.h"
#include "ladarsim/core/units.h"

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
            {"jitter", r.jitter},
            {"noise", r.noise},
            {"footprint_samples", r.footprint_samples},
            {"footprint_tolerance", r.footprint_tolerance},
            {"footprint_truncation", r.footprint_truncation}};
}

/// The initial map Algorithm 1 subtracts: a survey of the static world alone (the background map
/// and the objects that do not move, never a drone, bird or aircraft, nor a cloud or fog volume;
/// noise off) over every
/// direction the frames looked. When the gimbal moved, with beams at half the sensor's pitch over
/// the field it swept, so that a static surface's returns in any frame fall among the survey's
/// points; when every frame looked the same way (a fixed gimbal, a single frame), with the
/// sensor's own beams there: its frames fired in no other direction, and the survey costs one
/// frame's beams, not six. One centre sub-ray per beam: the map holds surfaces, not footprints.
/// Returns the number of points. The file is always written, with 0 points when the scene has
/// nothing static (or nothing static in view): one rule, so that its absence means a recorded
/// dataset.
std::size_t write_background_map(const Scenario& scenario, const std::vector<GimbalPointing>& pointings,
                                 const std::filesystem::path& file) {
    Scenario survey = scenario;
    // What does not move, but never a target: a drone, bird or aircraft hovering still is not part
    // of the map a detector subtracts (it would subtract the target itself). Nor a cloud or fog
    // volume: an initial map is surveyed on a clear day, and a medium's backscatter comes from
    // wherever its beams cross it, not from a surface; mapped, it would subtract whatever flies
    // inside it.
    std::erase_if(survey.scene.objects, [](const scene::SceneObject& o) {
        using scene::ObjectClass;
        const bool target = o.object_class == ObjectClass::drone || o.object_class == ObjectClass::bird ||
                            o.object_class == ObjectClass::plane;
        const bool medium = o.model && o.model->is_volume();
        return target || medium || !o.trajectory.is_static();
    });
    if ((survey.scene.objects.empty() && !survey.scene.background) || pointings.empty()) {
        write_frame_pcd(file, Frame{});
        return 0;
    }
    survey.mount.cue_object_id = 0;
    survey.render.noise = false;
    survey.render.jitter = false;
    survey.render.footprint_samples = 1;
    const bool one_pointing = std::all_of(pointings.begin(), pointings.end(), [&](const GimbalPointing& p) {
        return p.az_rad == pointings[0].az_rad && p.el_rad == pointings[0].el_rad;
    });
    if (one_pointing) {
        FrameRenderer renderer(survey);
        const Frame map = renderer.render_at(0, pointings[0]);
        write_frame_pcd(file, map);
        return map.returns.size();
    }
    double az_lo = pointings[0].az_rad, az_hi = az_lo, el_lo = pointings[0].el_rad, el_hi = el_lo;
    for (const auto& p : pointings) {
        az_lo = std::min(az_lo, p.az_rad), az_hi = std::max(az_hi, p.az_rad);
        el_lo = std::min(el_lo, p.el_rad), el_hi = std::max(el_hi, p.el_rad);
    }
    const ScanPattern& scan = *scenario.sensor.scan;
    const double pitch_az = scan.field_az_deg() * kDeg / scan.columns(), pitch_el = scan.field_el_deg() * kDeg / scan.rows();
    // The field swept by the gimbal, plus a tenth of the field on each side.
    const double field_az = std::min(2.0 * std::numbers::pi, az_hi - az_lo + 1.2 * scan.field_az_deg() * kDeg);
    const double field_el = std::min(std::numbers::pi, el_hi - el_lo + 1.2 * scan.field_el_deg() * kDeg);
    // Half the sensor's pitch, coarsened if needed to stay within four million survey beams.
    const double coarsen = std::max(1.0, std::sqrt(field_az / (0.5 * pitch_az) * field_el / (0.5 * pitch_el) / 4e6));
    // Surveyed as by a galvo raster; a sensor without one is timed as a 1 kHz sawtooth (a static
    // scene's survey times carry no information).
    const auto* galvo = dynamic_cast<const GalvoRaster*>(&scan);
    GalvoRaster::Parameters raster;
    raster.field_az_deg = field_az / kDeg;
    raster.field_el_deg = field_el / kDeg;
    raster.beams_az = static_cast<int>(std::ceil(field_az / (0.5 * pitch_az * coarsen)));
    raster.beams_el = static_cast<int>(std::ceil(field_el / (0.5 * pitch_el * coarsen)));
    raster.galvo_rate_hz = galvo ? galvo->parameters().galvo_rate_hz : 1000.0;
    raster.sweep = galvo ? galvo->parameters().sweep : GalvoSweep::sawtooth;
    raster.frame_rate_hz = scan.frame_rate_hz();
    survey.sensor.scan = std::make_shared<GalvoRaster>(raster);
    FrameRenderer renderer(survey);
    Frame map = renderer.render_at(0, GimbalPointing{0.5 * (az_lo + az_hi), 0.5 * (el_lo + el_hi)});
    write_frame_pcd(file, map);
    return map.returns.size();
}

/// The files of a render being staged beside its destination.
struct StagingFiles {
    std::filesystem::path staging, run_file, frames_dir;
    explicit StagingFiles(const std::filesystem::path& dir) : staging(dir), run_file(dir / "run.json"), frames_dir(dir / "frames") {}
    /// A finished frame's record (written last: its presence says the frame is complete) and ground truth.
    std::filesystem::path record_of(int k) const { return frames_dir / (frame_file_stem(static_cast<std::uint64_t>(k)) + ".log.json"); }
    std::filesystem::path truth_of(int k) const { return frames_dir / (frame_file_stem(static_cast<std::uint64_t>(k)) + ".truth.json"); }
};

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

/// Renders frame `k` into the staging directory: its PCD, EXR and ground truth, then its record.
void render_frame(FrameRenderer& renderer, int k, const StagingFiles& files) {
    using Clock = std::chrono::steady_clock;
    const auto started = Clock::now();
    const Frame frame = renderer.render(static_cast<std::uint64_t>(k));
    const double seconds = std::chrono::duration<double>(Clock::now() - started).count();
    const std::string stem = frame_file_stem(frame.index);
    write_frame_pcd(files.frames_dir / (stem + ".pcd"), frame);
    write_frame_exr(files.frames_dir / (stem + ".exr"), frame);
    write_ground_truth_json(files.truth_of(k), {ground_truth_of(frame)});
    std::map<std::uint32_t, std::uint64_t> counts;
    for (const auto& r : frame.returns) ++counts[r.object_id];
    nlohmann::json by_object = nlohmann::json::object();
    for (const auto& [id, count] : counts) by_object[std::to_string(id)] = count;
    write_json(files.record_of(k), {{"index", frame.index},
                                    {"start_time_s", frame.start_time_s},
                                    {"end_time_s", frame.end_time_s},
                                    {"gimbal_az_rad", frame.gimbal_az_rad},
                                    {"gimbal_el_rad", frame.gimbal_el_rad},
                                    {"returns", frame.returns.size()},
                                    {"returns_by_object", by_object},
                                    {"render_s", seconds}});
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
    std::string setup_error;
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
    DatasetSummary summary;
    summary.out_dir = out;
    std::string failure;
    bool stopped = false;
    // Every process takes the same number of turns, so that the collective checks line up.
    const int turns = (scenario.render.frames + team.size() - 1) / team.size();
    for (int turn = 0; turn < turns; ++turn) {
        const int k = turn * team.size() + team.rank();
        stopped = options.stop && options.stop->load();
        if (!stopped && k < scenario.render.frames && !std::filesystem::exists(files.record_of(k))) {
            try {
                if (k == options.fail_at_frame) throw std::runtime_error("failure injected for testing");
                render_frame(renderer, k, files);
            } catch (const std::exception& e) {
                failure = "frame " + std::to_string(k) + ": " + e.what();
            }
        }
        if (team.any(!failure.empty() || stopped)) break;
        if (options.progress && first_process) options.progress(std::min((turn + 1) * team.size(), scenario.render.frames), scenario.render.frames);
    }
    const bool any_failure = team.any(!failure.empty());
    if (any_failure) {
        // The finished frames stay, and hold their space on the disk: say where, and what to do.
        throw FrameFailure((failure.empty() ? "another process of the run failed" : failure) + "; finished frames are in " +
                           staging.string() + " (continue with --resume, or delete it to free its space)");
    }

    // What is on disk now: every record, from whichever process wrote it.
    std::vector<FrameGroundTruth> truth;
    std::vector<GimbalPointing> pointings;
    nlohmann::json frame_log = nlohmann::json::array();

    for (const int k : finished_frames(files, scenario.render.frames)) {
        nlohmann::json record = read_json(files.record_of(k));
        for (const auto& [id, count] : record.at("returns_by_object").items())
            summary.returns_by_object[static_cast<std::uint32_t>(std::stoul(id))] += count.get<std::uint64_t>();
        record.erase("returns_by_object");
        summary.returns += record.at("returns").get<std::uint64_t>();
        summary.render_seconds += record.at("render_s").get<double>();
        pointings.push_back({record.at("gimbal_az_rad").get<double>(), record.at("gimbal_el_rad").get<double>()});
        for (FrameGroundTruth& g : read_ground_truth_json(files.truth_of(k))) truth.push_back(std::move(g));
        frame_log.push_back(std::move(record));
    }
    summary.frames = static_cast<int>(frame_log.size());
    summary.beams_per_second =
        summary.render_seconds > 0.0 ? double(renderer.raster().beam_count()) * summary.frames / summary.render_seconds : 0.0;
    if (stopped || summary.frames < scenario.render.frames) {
        summary.interrupted = true;
        return summary;
    }
    if (!first_process) return summary;

    write_ground_truth_json(staging / "ground_truth.json", truth);
    summary.background_points = write_background_map(scenario, pointings, staging / "background.pcd");
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
