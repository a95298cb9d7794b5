// `ladarsim bench`: speed against accuracy (ladarsim_bench), summarised on stdout and written as JSON.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include "command.h"
#include "data_dir.h"
#include "plot_script.h"
#include "ladarsim/bench/benchmarks.h"
#include "ladarsim/core/json_file.h"

namespace ladarsim::apps {
namespace {

struct BenchCommand {
    bench::BenchOptions bench_options;
    std::string bench_json, bench_plot;

    CLI::App* add(CLI::App& app) {
        auto* bench_cmd = app.add_subcommand(
            "bench", "Measure speed against accuracy: our render against raw Embree on the same rays, the real-time factor "
                     "of the default scenario at each accuracy, beams/s against point-count/energy/range error for a drone "
                     "at 200, 1000, 2000 m, and scaling with beams, triangles and map points");
        bench_cmd->add_flag("--quick", bench_options.quick, "Fewer frames and sizes (about 3 min on 2 cores)");
        bench_cmd->add_option("--json", bench_json, "Write every figure to this JSON file");
        auto* plot = bench_cmd->add_option("--plot", bench_plot, "Draw speed against error into this PNG (needs python3-matplotlib)");
        bench_options.scenario = data_dir() / "scenarios" / "default.json";  // the bundled one, wherever it is installed
        bench_cmd->add_option("--scenario", bench_options.scenario, "Scenario to time")->check(CLI::ExistingFile)->capture_default_str();
        bench_cmd->add_option("--hard-case", bench_options.hard_case,
                              "Run only the hard cases whose name contains this (e.g. 'recorded map', 'edge'), nothing else")
            ->excludes(plot);  // the plot is of the accuracy curves, which a hard case alone does not measure
        bench_cmd->add_option("--map-scenario", bench_options.map_scenario,
                              "Scenario over a recorded map, for speed against error there (skipped if it cannot load: the map\n"
                              "lies in ../shared/data beside a checkout, so the default is found from a checkout's top)")
            ->capture_default_str();
        return bench_cmd;
    }

    int run() {
        const auto start = std::chrono::steady_clock::now();
        bench_options.progress = [start](const std::string& step) {
            std::fprintf(stderr, "[%5.0f s] %s\n",
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), step.c_str());
        };
        const nlohmann::json result = bench::run_benchmarks(bench_options);
        if (!bench_options.hard_case.empty()) {
            if (result["hard_cases"].empty()) throw std::runtime_error("--hard-case: no hard case's name contains '" + bench_options.hard_case + "'");
            print_hard_cases(result["hard_cases"]);
            return write(result);
        }
        const nlohmann::json& pipeline = result["pipeline"];
        std::printf("pipeline vs raw Embree (rays/s, same rays): %.2f (one frame on one thread: %.2f ms, its %.0f rays in Embree alone %.2f ms)\n",
                    result["pipeline_vs_raw_embree"].get<double>(), pipeline["pipeline_frame_ms"].get<double>(),
                    pipeline["rays"].get<double>(), pipeline["raw_embree_frame_ms"].get<double>());
        std::printf("real-time factor (default accuracy, vs the sensor's %.0f beams/s): %.1f\n",
                    result["realtime"]["sensor_beams_per_s"].get<double>(), result["realtime_factor"].get<double>());
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
        for (const nlohmann::json& p : result["peer"]["settings"]) {
            std::printf("plane and sphere, %s: %.0f pulses/s, %.1f rays and %.2f returns per pulse\n",
                        p["footprint_samples"] == 0 ? "adaptive" : "19 sub-rays", p["pulses_per_s"].get<double>(),
                        p["rays_per_pulse"].get<double>(), p["returns_per_pulse"].get<double>());
        }
        return write(result);
    }

    /// One line per hard case and setting: its errors against the reference and its speed.
    static void print_hard_cases(const nlohmann::json& cases) {
        for (const nlohmann::json& c : cases) {
            for (const nlohmann::json& s : c["settings"]) {
                const std::string setting = s.value("reference_with_another_seed", false) ? "reference, another seed"
                                            : s["footprint_samples"] == 0
                                                ? "adaptive " + std::to_string(s["footprint_tolerance"].get<double>()).substr(0, 5)
                                                : std::to_string(s["footprint_samples"].get<int>()) + " fixed";
                char with_targets[64] = "";
                if (s.contains("beams_off_with_targets_pct"))
                    std::snprintf(with_targets, sizeof with_targets, " (%.2f %% with a target too)", s["beams_off_with_targets_pct"].get<double>());
                std::printf("%s, %s: count %+.1f %%, energy %+.1f %%, range error mean %.1f / median %.1f mm, %.2f %% beams off%s, %d missing "
                            "beams, %.1f rays/beam, %.0f beams/s\n",
                            c["case"].get<std::string>().c_str(), setting.c_str(), s["count_error_pct"].get<double>(),
                            s["energy_error_pct"].get<double>(), s["mean_first_return_error_mm"].get<double>(),
                            s["median_first_return_error_mm"].get<double>(), s["beams_off_pct"].get<double>(), with_targets,
                            s["missing_beams"].get<int>(), s["rays_per_beam"].get<double>(), s["beams_per_s"].get<double>());
            }
        }
    }

    int write(const nlohmann::json& result) const {
        if (!bench_json.empty()) {
            write_json(bench_json, result);
            std::printf("wrote %s\n", bench_json.c_str());
        } else if (bench_plot.empty()) {
            std::cout << result.dump(2) << "\n";
        }
        if (!bench_plot.empty()) plot_figures("plot_bench.py", result, bench_json, bench_plot);
        return 0;
    }
};

}  // namespace

void add_bench_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<BenchCommand>(), exit_code);
}

}  // namespace ladarsim::apps
