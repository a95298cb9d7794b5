// `ladarsim make-assets`: the procedural glTF models ladarsim ships.
#include <cstdio>
#include <memory>
#include <string>

#include "command.h"
#include "ladarsim/scene/procedural_models.h"

namespace ladarsim::apps {
namespace {

struct MakeAssetsCommand {
    std::string assets_dir;

    CLI::App* add(CLI::App& app) {
        auto* assets = app.add_subcommand("make-assets", "Write the procedural glTF models ladarsim ships");
        assets->add_option("dir", assets_dir, "Output directory")->required();
        return assets;
    }

    int run() {
        scene::write_default_assets(assets_dir);
        std::printf("wrote the procedural models to %s\n", assets_dir.c_str());
        return 0;
    }
};

}  // namespace

void add_make_assets_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<MakeAssetsCommand>(), exit_code);
}

}  // namespace ladarsim::apps
