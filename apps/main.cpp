// The ladarsim command line: parses arguments and calls the libraries, nothing more.
#include <cstdio>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <optional>
#include <filesystem>
#include <exception>
#include <iostream>
#include <memory>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "ladarsim/bench/benchmarks.h"
#include "mpi_team.h"
#include "viewer_server.h"
#include "ladarsim/detect/expected_overlap.h"
#include "ladarsim/detect/sequence.h"
#include "ladarsim/dataset/input_error.h"
#include "ladarsim/scene/procedural_models.h"
#include "ladarsim/sensor_model/render_dataset.h"
#include "ladarsim/dataset/atomic_file.h"
#include "ladarsim/dataset/frame.h"
#include "ladarsim/dataset/json_file.h"
#include "ladarsim/sensor_model/target_point_counts.h"
#include "ladarsim/dataset/velodyne_pcap.h"
#include "ladarsim/dataset/dataset_directory.h"
#include "ladarsim/sensor_model/scenario.h"
#include "ladarsim/sensor_model/sensor_config.h"

namespace {

using namespace ladarsim;

void print_summary(const sensor_model::Scenario& scenario, const sensor_model::DatasetSummary& s) {
    std::printf("rendered %d frames of %s in %.2f s (%.0f beams/s, %.1fx the sensor's real time)\n", s.frames,
                scenario.file.string().c_str(), s.render_seconds, s.beams_per_second,
                s.beams_per_second / scenario.sensor.beams_per_second());
    std::printf("returns: %llu in all\n", static_cast<unsigned long long>(s.returns));
    for (const auto& [id, count] : s.returns_by_object) {
        std::string label = id == 0           ? "background map"
                            : id == kNoObject ? "false alarms (detector noise)"
                                              : "object " + std::to_string(id);
        for (const auto& o : scenario.scene.objects) {
            if (o.id == id) label += " (" + std::string(scene::to_string(o.object_class)) + (o.name.empty() ? "" : " " + o.name) + ")";
        }
        std::printf("  %-40s %10llu returns, %.1f per frame\n", label.c_str(), static_cast<unsigned long long>(count),
                    double(count) / s.frames);
    }
    std::printf("wrote %s/frames/NNNNNN.pcd (point clouds: PCL, CloudCompare), frames/NNNNNN.exr (range images),\n"
                "      ground_truth.json, manifest.json%s\n",
                s.out_dir.string().c_str(),
                s.background_points ? (" and background.pcd (" + std::to_string(s.background_points) +
                                       " points of the static scene)").c_str() : "");
}

/// Set by SIGINT/SIGTERM: the render loop stops after the frame it is on.
std::atomic<bool> g_stop{false};
extern "C" void request_stop(int) { g_stop.store(true); }

}  // namespace

int main(int argc, char** argv) {
    // Under mpirun: the ranks share the frames of `render`; otherwise MPI never starts.
    const std::unique_ptr<apps::MpiTeam> team = apps::MpiTeam::from_environment(&argc, &argv);
    CLI::App app{"ladarsim: a physically based LADAR simulator.\n"
                 "Renders ray-traced LADAR frames with ground truth from a scenario file."};
    app.require_subcommand(1);

    std::string out_dir;
    std::vector<std::string> scenario_files;
    int frames = 0, threads = 0, fail_at_frame = -1;
    std::uint64_t seed = 0;
    bool quiet = false;
    auto* render = app.add_subcommand(
        "render", "Render a scenario into a dataset directory. Under mpirun the frames are shared among the ranks\n"
                  "(mpirun -n N ladarsim render ...), with output identical to one process");
    render->add_option("scenario", scenario_files, "Scenario file(s) (JSON, see docs/scenario.md)")->required();
    render->add_option("--out", out_dir,
                       "Output directory (created; an earlier dataset there is replaced); with several scenarios, "
                       "one directory per scenario inside it, named after the file")
        ->required();
    render->add_option("--frames", frames, "Number of frames (default: the scenario's render.frames)")->check(CLI::PositiveNumber);
    render->add_option("--seed", seed, "Random seed (default: the scenario's render.seed)");
    render->add_option("--threads", threads, "Worker threads (default: all cores); output does not depend on it")
        ->check(CLI::NonNegativeNumber);
    render->add_flag("--quiet", quiet, "No progress output");
    bool resume = false;
    render->add_flag("--resume", resume,
                     "Continue a run interrupted by Ctrl-C or SIGTERM (its finished frames are kept in DIR.partial)");
    render->add_option("--fail-at-frame", fail_at_frame, "For testing: make this frame fail");

    auto* sensor = app.add_subcommand("sensor", "Sensor presets");
    sensor->require_subcommand(1);
    std::string preset = "paper_ladar";
    auto* show = sensor->add_subcommand("show", "Print a preset's parameters and derived quantities as JSON");
    show->add_option("--preset", preset, "Preset name")->check(CLI::IsMember(sensor_model::sensor_presets()));

    std::string table_json, table_markdown, table_plot;
    int table_frames = 50;
    auto* table1 = app.add_subcommand(
        "table1", "Check the paper's Table 1: its printed counts, its Eqs. 4-8 under a 0.5 and a 0.65 deg field, and the\n"
                  "returns rendered on a 0.3 m plate and quadcopter at each range (docs/table1.md)");
    table1->add_option("--json", table_json, "Write every number as JSON (a list of rows)");
    table1->add_option("--markdown", table_markdown, "Write the table as markdown");
    table1->add_option("--plot", table_plot, "Draw counts against range into this PNG (needs python3-matplotlib)");
    table1->add_option("--frames", table_frames, "Frames per range, target and noise setting (random sub-beam offsets)")
        ->check(CLI::PositiveNumber);
    table1->add_option("--seed", seed, "Random seed");
    int table_samples = 1024;
    table1->add_option("--footprint-samples", table_samples,
                       "Sub-rays per beam (converged at 1024: with the paper's power a beam whose footprint only\n"
                       "grazes the target still detects it, so sparse sub-rays under-count)")
        ->check(CLI::Range(1, 4096));

    std::string dataset_dir, detections_file, method_name = "vrbnn", eval_json, eval_plot;
    detect::DetectorConfig detector;
    std::uint32_t target_id = 0;
    auto* detect_cmd = app.add_subcommand("detect", "Run Algorithm 1 (background subtraction, (V-)RBNN, FIR or Kalman) over a dataset");
    detect_cmd->add_option("dir", dataset_dir, "Dataset directory (frames/*.pcd, background.pcd, ground_truth.json)")->required();
    detect_cmd->add_option("--method", method_name, "rbnn | vrbnn | kalman")->check(CLI::IsMember({"rbnn", "vrbnn", "kalman"}));
    detect_cmd->add_option("--out", detections_file, "Detections JSON (default DIR/detections-METHOD.json)");
    detect_cmd->add_option("--radius", detector.rbnn_radius_m, "RBNN radius, m");
    detect_cmd->add_option("--lambda", detector.lambda, "V-RBNN lambda (Algorithm 1: 7)");
    detect_cmd->add_option("--bias", detector.bias_m, "V-RBNN bias, m (Algorithm 1: 0.01)");
    detect_cmd->add_option("--resolution", detector.background_resolution_m, "Background octree voxel, m");
    detect_cmd->add_option("--min-box", detector.min_box_m, "Smallest box extent per axis, m (0: the cluster's own)");
    detect_cmd->add_option("--target", target_id, "Ground-truth id of the target to score (default: the first drone)");

    auto* eval_cmd = app.add_subcommand("eval", "Score detections against the ground truth: L2, IoU, EAO");
    eval_cmd->add_option("dir", dataset_dir, "Dataset directory")->required();
    eval_cmd->add_option("--detections", detections_file, "Detections JSON written by `ladarsim detect`")->required();
    eval_cmd->add_option("--json", eval_json, "Write the scores (mean_l2_m, mean_iou, eao, frames, failures, per frame)");
    eval_cmd->add_option("--plot", eval_plot, "Per-frame L2 and IoU curves into this PNG (needs python3-matplotlib)");

    std::string pcap_file;
    auto* import_cmd = app.add_subcommand("import-velodyne", "Decode a VLP-16 pcap capture into a dataset of recorded frames");
    import_cmd->add_option("pcap", pcap_file, "libpcap capture of VLP-16 packets")->required();
    import_cmd->add_option("--out", out_dir, "Output dataset directory")->required();

    std::string assets_dir;
    auto* assets = app.add_subcommand("make-assets", "Write the procedural glTF models ladarsim ships");
    assets->add_option("dir", assets_dir, "Output directory")->required();

    std::string view_dir;
    int view_port = 0;
    bool no_browser = false;
    auto* view_cmd = app.add_subcommand(
        "view", "Look at a rendered run in the browser: frames (background by range, target, clutter, false alarms),\n"
                "ground-truth and detected boxes, the field of view and the range image; serves on 127.0.0.1 only");
    view_cmd->add_option("dir", view_dir, "Dataset directory (as written by render; detect/eval results are shown)")->required();
    view_cmd->add_option("--port", view_port, "Port on 127.0.0.1 (default: a free one)")->check(CLI::Range(0, 65535));
    view_cmd->add_flag("--no-browser", no_browser, "Only print the URL");

    bench::BenchOptions bench_options;
    std::string bench_json;
    auto* bench_cmd = app.add_subcommand(
        "bench", "Measure speed against accuracy: our render against raw Embree on the same rays, the real-time factor "
                 "of the default scenario at each accuracy, beams/s against point-count/energy/range error for a drone "
                 "at 200, 1000, 2000 m, and scaling with beams, triangles and map points (plot: scripts/plot_bench.py)");
    bench_cmd->add_flag("--quick", bench_options.quick, "Fewer frames and sizes (about a minute)");
    bench_cmd->add_option("--json", bench_json, "Write every figure to this JSON file");
    bench_cmd->add_option("--scenario", bench_options.scenario, "Scenario to time")->check(CLI::ExistingFile)->capture_default_str();
    bench_cmd->add_option("--map-scenario", bench_options.map_scenario,
                          "Scenario over a recorded map, for speed against error there (skipped if it cannot load)")
        ->capture_default_str();

    CLI11_PARSE(app, argc, argv);
    spdlog::set_pattern("%^%l%$: %v");

    try {
        if (*render) {
            if (quiet || (team && team->rank() != 0)) spdlog::set_level(spdlog::level::warn);
            const bool speaking = !team || team->rank() == 0;
            for (const std::string& file : scenario_files) {
                const sensor_model::Scenario scenario = sensor_model::load_scenario(file);
                sensor_model::DatasetOptions options;
                options.out_dir = scenario_files.size() == 1 ? std::filesystem::path(out_dir)
                                                             : std::filesystem::path(out_dir) / std::filesystem::path(file).stem();
                if (render->count("--frames")) options.frames = frames;
                if (render->count("--seed")) options.seed = seed;
                // The ranks on one machine share its cores.
                options.threads = threads > 0 || !team
                                      ? threads
                                      : std::max(1, static_cast<int>(std::thread::hardware_concurrency()) / team->local_size());
                options.resume = resume;
                options.stop = &g_stop;
                options.team = team.get();
                options.fail_at_frame = fail_at_frame;
                std::signal(SIGINT, request_stop);
                std::signal(SIGTERM, request_stop);
                if (!quiet && speaking) {
                    options.progress = [](int done, int total) {
                        std::fprintf(stderr, "\rframe %d/%d", done, total);
                        if (done == total) std::fprintf(stderr, "\n");
                    };
                }
                const auto summary = sensor_model::render_dataset(scenario, options);
                if (summary.interrupted) {
                    if (speaking)
                        std::fprintf(stderr, "\ninterrupted after %d frames; finished frames are in %s.partial; continue with --resume\n",
                                     summary.frames, summary.out_dir.string().c_str());
                    return 130;
                }
                if (speaking) print_summary(scenario, summary);
            }
        } else if (*view_cmd) {
            apps::ViewerOptions options;
            options.run_dir = view_dir;
            options.viewer_dir = LADARSIM_SOURCE_DIR "/apps/viewer";
            options.port = view_port;
            std::signal(SIGINT, request_stop);
            std::signal(SIGTERM, request_stop);
            apps::serve_viewer(options, [&](const std::string& url) {
                std::printf("viewing %s at %s (Ctrl-C to stop)\n", view_dir.c_str(), url.c_str());
                std::fflush(stdout);
                if (!no_browser && std::system("command -v xdg-open >/dev/null 2>&1") == 0)
                    (void)!std::system(("xdg-open '" + url + "' >/dev/null 2>&1 &").c_str());
            }, g_stop);
        } else if (*bench_cmd) {
            const auto start = std::chrono::steady_clock::now();
            bench_options.progress = [start](const std::string& step) {
                std::fprintf(stderr, "[%5.0f s] %s\n",
                             std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), step.c_str());
            };
            const nlohmann::json result = bench::run_benchmarks(bench_options);
            std::printf("pipeline vs raw Embree (rays/s, same rays): %.2f\n", result["pipeline_vs_raw_embree"].get<double>());
            std::printf("real-time factor (default accuracy, vs %.0f beams/s): %.1f\n", bench::sensor_beams_per_second(),
                        result["realtime_factor"].get<double>());
            std::printf("target point-count error vs converged reference: %+.2f %%\n", result["count_error_pct"].get<double>());
            const nlohmann::json& map = result["recorded_map"];
            if (map.contains("skipped")) {
                std::printf("over a recorded map: skipped (%s)\n", map["skipped"].get<std::string>().c_str());
            } else {
                for (const nlohmann::json& m : map["settings"]) {
                    if (m["footprint_samples"] != 0) continue;
                    std::printf("over a recorded map, tolerance %.2f: %.0f rays/beam, real-time factor %.1f, map returns %+.1f %%, "
                                "map intensity %+.1f %%\n",
                                m["footprint_tolerance"].get<double>(), m["rays_per_beam"].get<double>(),
                                m["realtime_factor"].get<double>(), m["map_count_error_pct"].get<double>(),
                                m["map_energy_error_pct"].get<double>());
                }
            }
            if (!bench_json.empty()) {
                write_json(bench_json, result);
                std::printf("wrote %s\n", bench_json.c_str());
            } else {
                std::cout << result.dump(2) << "\n";
            }
        } else if (*show) {
            std::cout << sensor_model::to_json(sensor_model::sensor_preset(preset)).dump(2) << "\n";
        } else if (*table1) {
            // A 0.3 m square facing the sensor, the paper's abstraction of the drone.
            const auto plate = std::make_shared<scene::Model>(scene::make_plate(0.3, scene::kDefaultReflectance));
            const auto drone = std::make_shared<scene::Model>(scene::make_quadcopter());
            sensor_model::SensorConfig sensor = sensor_model::sensor_preset("paper_ladar");
            sensor.footprint_samples = table_samples;
            const nlohmann::json rows = sensor_model::table1_comparison(
                sensor, plate, drone, table_frames, table1->count("--seed") ? seed : 1,
                [](int done, int total) { std::fprintf(stderr, "\rrange %d/%d", done, total); if (done == total) std::fprintf(stderr, "\n"); });
            const std::string markdown = sensor_model::table1_markdown(rows);
            std::cout << markdown;
            if (!table_json.empty()) write_json(table_json, rows);
            if (!table_markdown.empty()) {
                AtomicFile out(table_markdown);
                out.stream() << markdown;
                out.commit();
            }
            if (!table_plot.empty()) {
                // The plot reads the numbers back from JSON, so it always shows what was written.
                const std::string json_for_plot = table_json.empty() ? table_plot + ".json" : table_json;
                if (table_json.empty()) write_json(json_for_plot, rows);
                const std::string command = "/usr/bin/python3 '" LADARSIM_SOURCE_DIR "/scripts/plot_table1.py' '" +
                                            json_for_plot + "' '" + table_plot + "'";
                if (std::system(command.c_str()) != 0) throw std::runtime_error("the plot script failed: " + command);
                if (table_json.empty()) std::filesystem::remove(json_for_plot);
            }
        } else if (*detect_cmd) {
            detector.method = detect::method_from_string(method_name);
            const detect::Sequence sequence = detect::load_sequence(dataset_dir);
            if (sequence.background.empty()) spdlog::warn("{}: no background.pcd: nothing is subtracted", dataset_dir);
            const auto detections = detect::detect_sequence(sequence, detector);
            nlohmann::json out = {{"method", method_name},
                                  {"config", {{"radius_m", detector.rbnn_radius_m}, {"lambda", detector.lambda},
                                              {"bias_m", detector.bias_m}, {"resolution_m", detector.background_resolution_m},
                                              {"min_neighbours", detector.min_neighbours}, {"max_diagonal_m", detector.max_diagonal_m},
                                              {"max_speed_mps", detector.max_speed_mps}, {"min_box_m", detector.min_box_m}}},
                                  {"detections", nlohmann::json::array()}};
            int found = 0, predicted = 0;
            for (const auto& d : detections) {
                out["detections"].push_back(detect::to_json(d));
                found += d.found && !d.predicted;
                predicted += d.predicted;
            }
            const auto target = target_id ? std::optional<std::uint32_t>(target_id) : detect::default_target(sequence);
            if (target) {
                // The supervised run EAO needs is only possible with ground truth; it is stored here so
                // that `eval` scores exactly what this configuration did.
                const auto run = detect::supervised_run(sequence, detector, *target);
                out["target"] = *target;
                out["supervised"] = {{"iou", run.iou}, {"initialised", run.initialised}, {"failures", run.failures}};
            }
            if (detections_file.empty()) detections_file = (std::filesystem::path(dataset_dir) / ("detections-" + method_name + ".json")).string();
            write_json(detections_file, out);
            std::printf("%s over %zu frames: %d detected, %d predicted, %zu without a box; wrote %s\n", method_name.c_str(),
                        detections.size(), found, predicted, detections.size() - found - predicted, detections_file.c_str());
        } else if (*eval_cmd) {
            const detect::Sequence sequence = detect::load_sequence(dataset_dir);
            const nlohmann::json in = read_json(detections_file);
            if (!in.contains("supervised") || !in.contains("target"))
                throw InputError(detections_file, "supervised", "missing: the dataset had no ground truth when detect ran");
            std::vector<detect::Detection> detections;
            for (const auto& j : in.at("detections")) detections.push_back(detect::detection_from_json(j));
            detect::SupervisedRun run;
            run.iou = in["supervised"]["iou"].get<std::vector<double>>();
            run.initialised = in["supervised"]["initialised"].get<std::vector<bool>>();
            run.failures = in["supervised"]["failures"].get<int>();
            const auto interval = detect::vot_length_interval({static_cast<int>(detections.size())});
            nlohmann::json scores = detect::evaluate(sequence, detections, run, in["target"].get<std::uint32_t>(), interval);
            scores["method"] = in.value("method", "");
            std::printf("%s: %zu frames, mean L2 %.3f m, mean IoU %.3f, EAO %.3f over lengths %d-%d, %d failures, %d frames lost\n",
                        scores["method"].get<std::string>().c_str(), detections.size(),
                        scores["mean_l2_m"].is_null() ? NAN : scores["mean_l2_m"].get<double>(), scores["mean_iou"].get<double>(),
                        scores["eao"].get<double>(), interval.first, interval.second, scores["failures"].get<int>(),
                        scores["frames_lost"].get<int>());
            const std::string json_path = eval_json.empty() && !eval_plot.empty() ? eval_plot + ".json" : eval_json;
            if (!json_path.empty()) write_json(json_path, scores);
            if (!eval_plot.empty()) {
                const std::string command = "/usr/bin/python3 '" LADARSIM_SOURCE_DIR "/scripts/plot_eval.py' '" + json_path +
                                            "' '" + eval_plot + "'";
                if (std::system(command.c_str()) != 0) throw std::runtime_error("the plot script failed: " + command);
                if (eval_json.empty()) std::filesystem::remove(json_path);
            }
        } else if (*import_cmd) {
            const auto frames = read_velodyne_vlp16_pcap(pcap_file);
            write_recorded_dataset(frames, sensor_model::to_json(sensor_model::sensor_preset("velodyne_vlp16")), out_dir, pcap_file);
            std::size_t returns = 0;
            for (const auto& f : frames) returns += f.returns.size();
            std::printf("decoded %zu frames, %zu returns from %s into %s/frames\n", frames.size(), returns, pcap_file.c_str(),
                        out_dir.c_str());
        } else if (*assets) {
            scene::write_default_assets(assets_dir);
            std::printf("wrote the procedural models to %s\n", assets_dir.c_str());
        }
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    } catch (const sensor_model::FrameFailure& e) {
        if (team && team->size() > 1) std::fprintf(stderr, "error: process %d of %d: %s\n", team->rank(), team->size(), e.what());
        else std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
