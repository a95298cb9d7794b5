#pragma once
// `render --dry-run`: what a render would cost, stated before anything is written.
#include <filesystem>

#include "ladarsim/sensor_model/render/scenario.h"

namespace ladarsim::apps {

/// Checks `scenario` and `out_dir` as a render does (geometry warnings, the output directory, the
/// disk) and prints its cost: frames, beams, and the time and disk space estimated from a few of
/// its frames (first, middle, last) rendered in memory and written to a temporary directory,
/// since a frame's cost varies tenfold along an approach. Writes nothing under `out_dir`.
void print_dry_run(const sensor_model::Scenario& scenario, int threads, const std::filesystem::path& out_dir);

}  // namespace ladarsim::apps
