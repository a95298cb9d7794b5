// `ladarsim render`: scenario files into dataset directories; under mpirun the ranks share the frames.
#include <algorithm>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include "command.h"
#include "dry_run.h"
#include "frame_budget.h"
#include "progress.h"
#include "option_checks.h"
#include "ladarsim/dataset/dataset_directory.h"
#include "ladarsim/dataset/frame.h"
#include "ladarsim/core/input_error.h"
#include "stop_signal.h"
#include "ladarsim/sensor_model/render/render_dataset.h"
#include "ladarsim/sensor_model/render/scenario.h"

namespace ladarsim::apps {
namespace {

void print_summary(const sensor_model::Scenario& scenario, const sensor_model::DatasetSummary& s) {
    std::printf("rendered %d frames of %s in %.2f s (%.0f beams/s, %.1fx real time: the sensor's %.0f beams/s)\n", s.frames,
                scenario.file.string().c_str(), s.render_seconds, s.beams_per_second,
                scenario.sensor.realtime_factor(s.beams_per_second), scenario.sensor.rated_beams_per_second());
    std::printf("returns: %llu in all\n", static_cast<unsigned long long>(s.returns));
    for (const auto& [id, count] : s.returns_by_object) {
        std::string label = id == 0                       ? "background map"
                            : id == kNoObject ? "false alarms (detector noise)"
                                                            : "object " + std::to_string(id);
        for (const auto& o : scenario.scene.objects) {
            if (o.id == id) label += " (" + std::string(scene::to_string(o.object_class)) + (o.name.empty() ? "" : " " + o.name) + ")";
        }
        std::printf("  %-40s %10llu returns, %.1f per frame\n", label.c_str(), static_cast<unsigned long long>(count),
                    double(count) / s.frames);
    }
    std::printf("wrote %s/frames/NNNNNN.pcd (point clouds: PCL, CloudCompare), frames/NNNNNN.exr (range images),\n"
                "      ground_truth.json, manifest.json and background.pcd (%s)\n",
                s.out_dir.string().c_str(),
                s.background_points ? (std::to_string(s.background_points) + " points of the static scene").c_str()
                                    : "0 points: nothing static in view, nothing for detection to subtract");
    if (!s.kept.empty()) std::printf("%s\n", kept_files_note(s.kept, s.out_dir).c_str());
}

struct RenderCommand {
    const std::unique_ptr<MpiTeam>& team;
    std::string out_dir;
    std::vector<std::string> scenario_files;
    int frames = 0, threads = 0, fail_at_frame = -1;
    std::uint64_t seed = 0;
    bool quiet = false;
    bool resume = false;
    bool dry_run = false;
    CLI::App* render = nullptr;

    explicit RenderCommand(const std::unique_ptr<MpiTeam>& team) : team(team) {}

    CLI::App* add(CLI::App& app) {
        render = app.add_subcommand(
            "render", "Render a scenario into a dataset directory. Under mpirun the frames are shared among the ranks\n"
                      "(mpirun -n N ladarsim render ...), with output identical to one process");
        render->add_option("scenario", scenario_files, "Scenario file(s) (JSON, see docs/scenario.md)")->required();
        render->add_option("--out", out_dir,
                           "Output directory (created; an earlier dataset's files there are replaced, yours beside them kept); with several scenarios, "
                           "one directory per scenario inside it, named after the file")
            ->required();
        render->add_option("--frames", frames, "Number of frames (default: the scenario's render.frames)")
            ->check(whole_number(1, sensor_model::kMaxFrames));
        render->add_option("--seed", seed, "Random seed (default: the scenario's render.seed)")
            ->check(whole_number(0, std::numeric_limits<std::uint64_t>::max()));
        render->add_option("--threads", threads,
                           "Worker threads (0, the default: all cores); output does not depend on it. From 8, a frame per 4 "
                           "threads renders at once, each with its own copy of the scene")
            ->check(whole_number(0, std::numeric_limits<int>::max()));
        render->add_flag("--quiet", quiet, "No progress output");
        render->add_flag("--dry-run", dry_run,
                         "Check the scenario and --out, and state the cost (frames, beams, time and disk, estimated from its "
                         "first, middle and last frames rendered in memory) without writing the dataset");
        render->add_flag("--resume", resume,
                         "Continue a run interrupted by Ctrl-C or SIGTERM (its finished frames are kept in DIR.partial)");
        // For the tests only: not in --help.
        render->add_option("--fail-at-frame", fail_at_frame, "For testing: make this frame fail")->group("");
        return render;
    }

    int run() {
        if (quiet || (team && team->rank() != 0)) spdlog::set_level(spdlog::level::warn);
        const bool speaking = !team || team->rank() == 0;
        // Several scenarios: one directory each, named after the file; two of one name would
        // overwrite each other, so they are refused before anything is rendered.
        std::vector<std::filesystem::path> out_dirs;
        for (const std::string& file : scenario_files) {
            const std::filesystem::path dir = scenario_files.size() == 1 ? std::filesystem::path(out_dir)
                                                                          : std::filesystem::path(out_dir) / std::filesystem::path(file).stem();
            if (const auto same = std::find(out_dirs.begin(), out_dirs.end(), dir); same != out_dirs.end())
                throw InputError(file, "scenario",
                                 "renders into " + dir.string() + ", as " + scenario_files[same - out_dirs.begin()] +
                                     " does (one directory per scenario file name); give each scenario file its own name");
            out_dirs.push_back(dir);
        }
        for (std::size_t i = 0; i < scenario_files.size(); ++i) {
            const std::string& file = scenario_files[i];
            std::signal(SIGINT, request_stop);
            std::signal(SIGTERM, request_stop);
            // Under mpirun the ranks stop together after their frames (a rank ending alone would
            // leave the others waiting).
            if (!team)
                stop_within_a_second("\ninterrupted; the finished frames are in " + out_dirs[i].string() +
                                     ".partial; continue with --resume\n");
            // The ranks on one machine share its cores; loading (a recorded map's normals) keeps
            // to the threads asked for, as rendering does.
            const int workers = threads > 0 || !team
                                    ? threads
                                    : std::max(1, static_cast<int>(std::thread::hardware_concurrency()) / team->local_size());
            std::optional<tbb::global_control> parallelism;
            if (workers > 0) parallelism.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(workers));
            const sensor_model::Scenario scenario = sensor_model::load_scenario(file);
            const bool frames_given = render->count("--frames") > 0;
            check_frames_fit_on_disk(frames_given ? frames : scenario.render.frames, frames_given ? std::to_string(frames) : file,
                                     frames_given ? "--frames" : "render.frames", out_dirs[i]);
            if (dry_run) {
                sensor_model::Scenario costed = scenario;
                if (frames_given) costed.render.frames = frames;
                if (render->count("--seed")) costed.render.seed = seed;
                if (speaking) print_dry_run(costed, threads, out_dirs[i]);
                continue;
            }
            sensor_model::DatasetOptions options;
            options.out_dir = out_dirs[i];
            if (frames_given) options.frames = frames;
            if (render->count("--seed")) options.seed = seed;
            options.threads = workers;
            options.resume = resume;
            options.stop = &g_stop;
            options.team = team.get();
            options.fail_at_frame = fail_at_frame;
            if (!quiet && speaking) options.progress = progress_lines("frame");
            const auto summary = sensor_model::render_dataset(scenario, options);
            acknowledge_stop();
            if (summary.interrupted) {
                if (speaking)
                    std::fprintf(stderr, "%sinterrupted after %d frames; finished frames are in %s.partial; continue with --resume\n",
                                 !quiet && stderr_is_terminal() ? "\n" : "", summary.frames, summary.out_dir.string().c_str());
                return 130;
            }
            if (speaking) print_summary(scenario, summary);
        }
        return 0;
    }
};

}  // namespace

void add_render_command(CLI::App& app, int& exit_code, const std::unique_ptr<MpiTeam>& team) {
    add_command(app, std::make_shared<RenderCommand>(team), exit_code);
}

}  // namespace ladarsim::apps
