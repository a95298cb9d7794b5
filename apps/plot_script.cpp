#include "plot_script.h"

#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <vector>

extern char** environ;

namespace ladarsim::apps {

void run_plot_script(const std::string& script, const std::string& json_path, const std::string& out_path) {
    // Run directly, not through a shell: a path holding a quote or a '$' stays one argument.
    const std::string python = "/usr/bin/python3", path = LADARSIM_SOURCE_DIR "/scripts/" + script;
    std::vector<std::string> args = {python, path, json_path, out_path};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const std::string command = python + " " + path + " " + json_path + " " + out_path;
    pid_t pid = 0;
    if (const int error = ::posix_spawn(&pid, python.c_str(), nullptr, nullptr, argv.data(), environ); error != 0)
        throw std::runtime_error("cannot run the plot script (" + std::string(std::strerror(error)) + "): " + command);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) throw std::runtime_error("lost the plot script: " + command);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw std::runtime_error("the plot script failed: " + command);
}

}  // namespace ladarsim::apps
