// The ladarsim command line: parses arguments and calls the libraries, nothing more.
#include <cstdio>
#include <exception>
#include <iostream>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "ladarsim/scene/input_error.h"
#include "ladarsim/scene/procedural_models.h"
#include "ladarsim/sensor_model/dataset.h"
#include "ladarsim/sensor_model/frame.h"
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
        std::string label = id == 0                       ? "background map"
                            : id == sensor_model::kNoObject ? "false alarms (detector noise)"
                                                            : "object " + std::to_string(id);
        for (const auto& o : scenario.scene.objects) {
            if (o.id == id) label += " (" + std::string(scene::to_string(o.object_class)) + (o.name.empty() ? "" : " " + o.name) + ")";
        }
        std::printf("  %-40s %10llu returns, %.1f per frame\n", label.c_str(), static_cast<unsigned long long>(count),
                    double(count) / s.frames);
    }
    std::printf("wrote %s/frames/NNNNNN.pcd (point clouds: PCL, CloudCompare), frames/NNNNNN.exr (range images),\n"
                "      ground_truth.json and manifest.json\n",
                s.out_dir.string().c_str());
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"ladarsim: a physically based LADAR simulator.\n"
                 "Renders ray-traced LADAR frames with ground truth from a scenario file."};
    app.require_subcommand(1);

    std::string scenario_file, out_dir;
    int frames = 0, threads = 0;
    std::uint64_t seed = 0;
    bool quiet = false;
    auto* render = app.add_subcommand("render", "Render a scenario into a dataset directory");
    render->add_option("scenario", scenario_file, "Scenario file (JSON, see docs/scenario.md)")->required();
    render->add_option("--out", out_dir, "Output directory (created; existing frames are overwritten)")->required();
    render->add_option("--frames", frames, "Number of frames (default: the scenario's render.frames)")->check(CLI::PositiveNumber);
    render->add_option("--seed", seed, "Random seed (default: the scenario's render.seed)");
    render->add_option("--threads", threads, "Worker threads (default: all cores); output does not depend on it")
        ->check(CLI::NonNegativeNumber);
    render->add_flag("--quiet", quiet, "No progress output");

    auto* sensor = app.add_subcommand("sensor", "Sensor presets");
    sensor->require_subcommand(1);
    std::string preset = "paper_ladar";
    auto* show = sensor->add_subcommand("show", "Print a preset's parameters and derived quantities as JSON");
    show->add_option("--preset", preset, "Preset name")->check(CLI::IsMember(sensor_model::sensor_presets()));

    std::string assets_dir;
    auto* assets = app.add_subcommand("make-assets", "Write the procedural glTF models ladarsim ships");
    assets->add_option("dir", assets_dir, "Output directory")->required();

    CLI11_PARSE(app, argc, argv);
    spdlog::set_pattern("%^%l%$: %v");

    try {
        if (*render) {
            if (quiet) spdlog::set_level(spdlog::level::warn);
            const sensor_model::Scenario scenario = sensor_model::load_scenario(scenario_file);
            sensor_model::DatasetOptions options;
            options.out_dir = out_dir;
            if (render->count("--frames")) options.frames = frames;
            if (render->count("--seed")) options.seed = seed;
            options.threads = threads;
            if (!quiet) {
                options.progress = [](int done, int total) {
                    std::fprintf(stderr, "\rframe %d/%d", done, total);
                    if (done == total) std::fprintf(stderr, "\n");
                };
            }
            print_summary(scenario, sensor_model::render_dataset(scenario, options));
        } else if (*show) {
            std::cout << sensor_model::to_json(sensor_model::sensor_preset(preset)).dump(2) << "\n";
        } else if (*assets) {
            scene::write_default_assets(assets_dir);
            std::printf("wrote the procedural models to %s\n", assets_dir.c_str());
        }
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
