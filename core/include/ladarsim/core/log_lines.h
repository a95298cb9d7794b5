#pragma once
// How ladarsim's log lines read, wherever it runs: "warning: FILE: what", on stderr (coloured on
// a terminal), the same from the command line and from the Python module. Header-only: core does
// not link spdlog; whoever calls this does.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

namespace ladarsim {

inline void use_ladarsim_log_lines() {
    spdlog::set_default_logger(spdlog::stderr_color_mt("ladarsim"));
    spdlog::set_pattern("%^%l%$: %v");
}

}  // namespace ladarsim
