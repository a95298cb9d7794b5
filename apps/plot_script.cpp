#include "plot_script.h"

#include <cstdlib>
#include <stdexcept>

namespace ladarsim::apps {

void run_plot_script(const std::string& script, const std::string& json_path, const std::string& png_path) {
    const std::string command = "/usr/bin/python3 '" LADARSIM_SOURCE_DIR "/scripts/" + script + "' '" + json_path + "' '" +
                                png_path + "'";
    if (std::system(command.c_str()) != 0) throw std::runtime_error("the plot script failed: " + command);
}

}  // namespace ladarsim::apps
