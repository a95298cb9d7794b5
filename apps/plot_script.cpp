#include "plot_script.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "data_dir.h"
#include "ladarsim/core/json_file.h"

extern char** environ;

namespace ladarsim::apps {

namespace {

// Debian's own interpreter: its matplotlib is the one scripts/setup.sh installs (another python3
// first on PATH, a pyenv's, would have none).
constexpr const char* kPython = "/usr/bin/python3";

/// The last non-empty line of `text`: a Python traceback's or sys.exit's message.
std::string last_line(const std::string& text) {
    const std::size_t end = text.find_last_not_of("\r\n");
    if (end == std::string::npos) return "no message";
    const std::size_t newline = text.find_last_of('\n', end);
    const std::size_t start = newline == std::string::npos ? 0 : newline + 1;
    return text.substr(start, end + 1 - start);
}

}  // namespace

void run_plot_script(const std::string& script, const std::vector<std::string>& arguments) {
    std::vector<std::string> words = {kPython, data_file("scripts/" + script).string()};
    words.insert(words.end(), arguments.begin(), arguments.end());
    std::vector<char*> argv;
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);

    // The script's stderr comes back through a pipe, so that a failure is reported in one line.
    int pipe_fds[2];
    if (pipe2(pipe_fds, O_CLOEXEC) != 0) throw std::runtime_error(std::string("cannot open a pipe: ") + std::strerror(errno));
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDERR_FILENO);
    std::fflush(stdout);  // what the command printed comes before what the script prints
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, kPython, &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    close(pipe_fds[1]);
    if (spawned != 0) {
        close(pipe_fds[0]);
        throw std::runtime_error(std::string("cannot run ") + kPython + " for " + script + ": " + std::strerror(spawned) +
                                 " (scripts/setup.sh installs it with matplotlib)");
    }
    std::string messages;
    char buffer[4096];
    for (;;) {
        const ssize_t n = read(pipe_fds[0], buffer, sizeof buffer);
        if (n > 0) messages.append(buffer, static_cast<std::size_t>(n));
        else if (n == 0 || errno != EINTR) break;
    }
    close(pipe_fds[0]);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
        std::fputs(messages.c_str(), stderr);
        return;
    }
    const std::string how = WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                              : std::string("signal ") + strsignal(WTERMSIG(status));
    throw std::runtime_error(script + " failed (" + how + "): " + last_line(messages));
}

void plot_figures(const std::string& script, const nlohmann::json& figures, const std::string& json_path,
                  const std::string& png_path) {
    if (!json_path.empty()) return run_plot_script(script, {json_path, png_path});
    std::string temporary = (std::filesystem::temp_directory_path() / "ladarsim-figures-XXXXXX.json").string();
    const int fd = mkstemps(temporary.data(), 5);
    if (fd < 0) throw std::runtime_error("cannot create " + temporary + ": " + std::strerror(errno));
    close(fd);
    struct Removed {
        std::string path;
        ~Removed() {
            std::error_code ignored;
            std::filesystem::remove(path, ignored);
        }
    } removed{temporary};
    write_json(temporary, figures);
    run_plot_script(script, {temporary, png_path});
}

}  // namespace ladarsim::apps
