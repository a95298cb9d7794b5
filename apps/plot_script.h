#pragma once
// The plots of `table1`, `eval` and `campaign`: a script in scripts/ draws from the JSON the
// command wrote.
#include <string>

namespace ladarsim::apps {

/// Runs `/usr/bin/python3 scripts/<script> <json_path> <out_path>` without a shell (needs
/// python3-matplotlib); throws std::runtime_error naming the command when it fails.
void run_plot_script(const std::string& script, const std::string& json_path, const std::string& out_path);

}  // namespace ladarsim::apps
