#pragma once
// The plots of `eval`, `table1`, `bench`, `preview` and `campaign`: a Python script from
// ladarsim's data (share/ladarsim/scripts/) draws what the command wrote.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace ladarsim::apps {

/// Runs `/usr/bin/python3 <data_dir>/scripts/<script> <arguments...>` directly, without a shell, so
/// any path is passed as it is; waits for it. The script's stdout is the program's; its stderr is
/// passed on when it succeeds. Throws InputError when the script is not installed and
/// std::runtime_error with the script's last line of stderr when it cannot run or fails.
void run_plot_script(const std::string& script, const std::vector<std::string>& arguments);

/// Runs `script JSON png_path`, JSON being `json_path` (which must already hold `figures`) or, when
/// that is empty, a private temporary file holding them, removed afterwards: the plot always shows
/// what was written, and no file is left beside the user's.
void plot_figures(const std::string& script, const nlohmann::json& figures, const std::string& json_path,
                  const std::string& png_path);

}  // namespace ladarsim::apps
