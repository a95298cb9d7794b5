// `ladarsim view`: a rendered run in the browser, served on 127.0.0.1 until Ctrl-C.
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "command.h"
#include "data_dir.h"
#include "stop_signal.h"
#include "viewer_server.h"

namespace ladarsim::apps {
namespace {

struct ViewCommand {
    std::string view_dir;
    int view_port = 0;
    bool no_browser = false;

    CLI::App* add(CLI::App& app) {
        auto* view_cmd = app.add_subcommand(
            "view", "Look at a rendered run in the browser: frames (background by range, target, clutter, false alarms),\n"
                    "ground-truth and detected boxes, the field of view and the range image; serves on 127.0.0.1 only");
        view_cmd->add_option("dir", view_dir, "Dataset directory (as written by render; detect/eval results are shown)")->required();
        view_cmd->add_option("--port", view_port, "Port on 127.0.0.1 (default: a free one)")->check(CLI::Range(0, 65535));
        view_cmd->add_flag("--no-browser", no_browser, "Only print the URL");
        return view_cmd;
    }

    int run() {
        apps::ViewerOptions options;
        options.run_dir = view_dir;
        options.viewer_dir = data_file("viewer");
        options.port = view_port;
        std::signal(SIGINT, request_stop);
        std::signal(SIGTERM, request_stop);
        apps::serve_viewer(options, [&](const std::string& url) {
            std::printf("viewing %s at %s (Ctrl-C to stop)\n", view_dir.c_str(), url.c_str());
            std::fflush(stdout);
            if (!no_browser && std::system("command -v xdg-open >/dev/null 2>&1") == 0)
                (void)!std::system(("xdg-open '" + url + "' >/dev/null 2>&1 &").c_str());
        }, g_stop);
        return 0;
    }
};

}  // namespace

void add_view_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<ViewCommand>(), exit_code);
}

}  // namespace ladarsim::apps
