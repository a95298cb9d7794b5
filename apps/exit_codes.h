#pragma once
// What a failed command prints and returns: one line on stderr and a non-zero exit code.
#include <functional>

#include <CLI/CLI.hpp>

#include "mpi_team.h"

namespace ladarsim::apps {

/// Runs `command` and returns its exit code. What it throws becomes "error: <message>" on stderr
/// and exit 2 for bad input (InputError), else 1; a failed frame names the process when `team`
/// has several.
int exit_code_of(const std::function<int()>& command, const MpiTeam* team);

/// Before parsing: when the first argument is not an option and names no subcommand of `app`, or
/// there is none, prints one line naming it (or its absence) and the valid subcommands, and
/// returns 2; else 0.
int check_subcommand(const CLI::App& app, int argc, const char* const* argv);

}  // namespace ladarsim::apps
