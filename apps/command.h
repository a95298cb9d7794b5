#pragma once
// The subcommands of `ladarsim`, one file each. Each adds its subcommand to the app with its options
// bound to the members of a small struct; CLI11 runs the one parsed as that subcommand's callback.
#include <memory>

#include <CLI/CLI.hpp>

#include "mpi_team.h"

namespace ladarsim::apps {

/// Adds `command` to `app`: `command->add(app)` declares its subcommand and options and returns the
/// subcommand whose parsing runs it; then `command->run()` does the work and `exit_code` receives
/// what it returns. The callback shares ownership, so the bound members outlive the parse.
template <class Command>
void add_command(CLI::App& app, std::shared_ptr<Command> command, int& exit_code) {
    command->add(app)->callback([command, &exit_code] { exit_code = command->run(); });
}

void add_render_command(CLI::App& app, int& exit_code, const std::unique_ptr<MpiTeam>& team);
void add_campaign_command(CLI::App& app, int& exit_code);
void add_sensor_command(CLI::App& app, int& exit_code);
void add_table1_command(CLI::App& app, int& exit_code);
void add_detect_command(CLI::App& app, int& exit_code);
void add_eval_command(CLI::App& app, int& exit_code);
void add_benchmark_command(CLI::App& app, int& exit_code);
void add_import_velodyne_command(CLI::App& app, int& exit_code);
void add_import_ouster_command(CLI::App& app, int& exit_code);
void add_export_kitti_command(CLI::App& app, int& exit_code);
void add_export_las_command(CLI::App& app, int& exit_code);
void add_make_assets_command(CLI::App& app, int& exit_code);
void add_train_classifier_command(CLI::App& app, int& exit_code);
void add_preview_command(CLI::App& app, int& exit_code);
void add_view_command(CLI::App& app, int& exit_code);
void add_bench_command(CLI::App& app, int& exit_code);

}  // namespace ladarsim::apps
