// The ladarsim command line: builds the app from the subcommands (one file each, see command.h),
// parses the arguments and runs the subcommand given, nothing more.
#include <cstdio>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "command.h"
#include "ladarsim/core/log_lines.h"
#include "ladarsim/dataset/dataset_directory.h"
#include "exit_codes.h"
#include "mpi_team.h"

int main(int argc, char** argv) {
    using namespace ladarsim;
    // Under mpirun: the ranks share the frames of `render`; otherwise MPI never starts.
    const std::unique_ptr<apps::MpiTeam> team = apps::MpiTeam::from_environment(&argc, &argv);
    CLI::App app{"ladarsim: a physically based LADAR simulator.\n"
                 "Renders ray-traced LADAR frames with ground truth from a scenario file."};
    app.require_subcommand(1);

    // In the order `ladarsim --help` lists them.
    int exit_code = 0;
    apps::add_render_command(app, exit_code, team);
    apps::add_campaign_command(app, exit_code);
    apps::add_sensor_command(app, exit_code);
    apps::add_table1_command(app, exit_code);
    apps::add_detect_command(app, exit_code);
    apps::add_eval_command(app, exit_code);
    apps::add_benchmark_command(app, exit_code);
    apps::add_import_velodyne_command(app, exit_code);
    apps::add_import_ouster_command(app, exit_code);
    apps::add_export_kitti_command(app, exit_code);
    apps::add_export_las_command(app, exit_code);
    apps::add_make_assets_command(app, exit_code);
    apps::add_train_classifier_command(app, exit_code);
    apps::add_preview_command(app, exit_code);
    apps::add_view_command(app, exit_code);
    apps::add_bench_command(app, exit_code);

    // Diagnostics on stderr, results on stdout.
    const std::string version = "ladarsim " + software_json().at("version").get<std::string>();
    app.set_version_flag("--version", version);
    // After a subcommand too (`ladarsim render --version`), where CLI11 would first ask for the
    // subcommand's required arguments.
    for (int i = 1; i < argc; ++i)
        if (std::string(argv[i]) == "--version") {
            std::printf("%s\n", version.c_str());
            return 0;
        }
    // CLI11 says "A subcommand is required" for a misspelt one too: name it, and list the valid ones.
    if (const int code = apps::check_subcommand(app, argc, argv); code != 0) return code;

    use_ladarsim_log_lines();
    // The parsed subcommand runs inside parse(), as its callback.
    return apps::exit_code_of(
        [&] {
            CLI11_PARSE(app, argc, argv);
            return exit_code;
        },
        team.get());
}
