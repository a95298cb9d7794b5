// `ladarsim table1`: the paper's Table 1 against its equations and rendered counts (docs/table1.md).
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>
#include <string>

#include <tbb/global_control.h>
#include <tbb/info.h>

#include "command.h"
#include "progress.h"
#include "option_checks.h"
#include "plot_script.h"
#include "ladarsim/experiments/table1.h"
#include "ladarsim/scene/procedural_models.h"
#include "ladarsim/core/atomic_file.h"
#include "ladarsim/core/json_file.h"
#include "ladarsim/sensor_model/sensor/sensor.h"

namespace ladarsim::apps {
namespace {

struct Table1Command {
    std::string table_json, table_markdown, table_plot;
    int table_frames = 50;
    std::uint64_t seed = 0;
    int table_samples = 1024;
    int threads = 0;
    CLI::App* table1 = nullptr;

    CLI::App* add(CLI::App& app) {
        table1 = app.add_subcommand(
            "table1", "Check the paper's Table 1: its printed counts, its Eqs. 4-8 under a 0.5 and a 0.65 deg field, and the\n"
                      "returns rendered on a 0.3 m plate and quadcopter at each range (docs/table1.md). Renders\n"
                      "7 ranges x 4 settings x --frames frames: about 6 min on 2 cores with the defaults");
        table1->add_option("--json", table_json, "Write every number as JSON (a list of rows)");
        table1->add_option("--markdown", table_markdown, "Write the table as markdown");
        table1->add_option("--plot", table_plot, "Draw counts against range into this PNG (needs python3-matplotlib)");
        table1->add_option("--frames", table_frames, "Frames per range, target and noise setting (random sub-beam offsets)")
            ->check(whole_number(1, std::numeric_limits<int>::max()));
        table1->add_option("--seed", seed, "Random seed")->check(whole_number(0, std::numeric_limits<std::uint64_t>::max()));
        table1->add_option("--footprint-samples", table_samples,
                           "Sub-rays per beam (converged at 1024: with the paper's power a beam whose footprint only\n"
                           "grazes the target still detects it, so sparse sub-rays under-count)")
            ->check(CLI::Range(1, 4096));
        table1->add_option("--threads", threads, "Worker threads (0, the default: all cores); output does not depend on it")
            ->check(whole_number(0, std::numeric_limits<int>::max()));
        return table1;
    }

    int run() {
        const int workers = threads > 0 ? threads : tbb::info::default_concurrency();
        tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(workers));
        // A 0.3 m square facing the sensor, the paper's abstraction of the drone.
        const auto plate = std::make_shared<scene::Model>(scene::make_plate(0.3, scene::kDefaultReflectance));
        const auto drone = std::make_shared<scene::Model>(scene::make_quadcopter());
        const nlohmann::json rows = experiments::table1_comparison(
            sensor_model::sensor_preset("paper_ladar"), table_samples, plate, drone, table_frames, table1->count("--seed") ? seed : 1,
            progress_lines("frames"));
        const std::string markdown = experiments::table1_markdown(rows);
        std::cout << markdown;
        if (!table_json.empty()) write_json(table_json, rows);
        if (!table_markdown.empty()) {
            AtomicFile out(table_markdown);
            out.stream() << markdown;
            out.commit();
        }
        if (!table_plot.empty()) plot_figures("plot_table1.py", rows, table_json, table_plot);
        return 0;
    }
};

}  // namespace

void add_table1_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<Table1Command>(), exit_code);
}

}  // namespace ladarsim::apps
