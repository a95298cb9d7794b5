#pragma once
// What a failed command prints and returns: one line on stderr and a non-zero exit code.
#include <functional>

#include "mpi_team.h"

namespace ladarsim::apps {

/// Runs `command` and returns its exit code. What it throws becomes "error: <message>" on stderr
/// and exit 2 for bad input (InputError), else 1; a failed frame names the process when `team`
/// has several.
int exit_code_of(const std::function<int()>& command, const MpiTeam* team);

}  // namespace ladarsim::apps
