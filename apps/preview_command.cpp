// `ladarsim preview`: DIR/preview.png, frames of a rendered dataset with their ground-truth boxes
// (scripts/preview.py, from ladarsim's data).
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "command.h"
#include "option_checks.h"
#include "plot_script.h"

namespace ladarsim::apps {
namespace {

struct PreviewCommand {
    std::string dataset_dir;
    int frames = 4;
    bool force = false;

    CLI::App* add(CLI::App& app) {
        auto* preview = app.add_subcommand(
            "preview", "Draw DIR/preview.png: frames of a rendered dataset, points by range, with each object's box and\n"
                       "a close-up of the first drone (needs python3-matplotlib)");
        preview->add_option("dir", dataset_dir, "Dataset directory (as written by render)")->required()->check(CLI::ExistingDirectory);
        preview->add_option("--frames", frames, "Frames to draw, evenly spaced")
            ->check(whole_number(1, std::numeric_limits<int>::max()))
            ->capture_default_str();
        preview->add_flag("--force", force, "Replace DIR/preview.png even if ladarsim did not write it");
        return preview;
    }

    int run() {
        // "--" ends the script's options, so a directory named like one is still the directory.
        std::vector<std::string> arguments = {"--frames", std::to_string(frames)};
        if (force) arguments.push_back("--force");
        arguments.insert(arguments.end(), {"--", dataset_dir});
        run_plot_script("preview.py", arguments);
        return 0;
    }
};

}  // namespace

void add_preview_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<PreviewCommand>(), exit_code);
}

}  // namespace ladarsim::apps
