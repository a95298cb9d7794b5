#pragma once
// The plots of `table1` and `eval`: a script in scripts/ draws a PNG from the JSON the command wrote.
#include <string>

namespace ladarsim::apps {

/// Runs `/usr/bin/python3 scripts/<script> <json_path> <png_path>` (needs python3-matplotlib);
/// throws std::runtime_error naming the command when it fails.
void run_plot_script(const std::string& script, const std::string& json_path, const std::string& png_path);

}  // namespace ladarsim::apps
