// `ladarsim sensor show`: a sensor preset and its derived quantities as JSON.
#include <iostream>
#include <memory>
#include <string>

#include "command.h"
#include "ladarsim/sensor_model/sensor.h"

namespace ladarsim::apps {
namespace {

struct SensorCommand {
    std::string preset = "paper_ladar";

    CLI::App* add(CLI::App& app) {
        auto* sensor = app.add_subcommand("sensor", "Sensor presets");
        sensor->require_subcommand(1);
        auto* show = sensor->add_subcommand("show", "Print a preset's parameters and derived quantities as JSON");
        show->add_option("--preset", preset, "Preset name")->check(CLI::IsMember(sensor_model::sensor_presets()));
        return show;
    }

    int run() {
        std::cout << sensor_model::to_json(sensor_model::sensor_preset(preset)).dump(2) << "\n";
        return 0;
    }
};

}  // namespace

void add_sensor_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<SensorCommand>(), exit_code);
}

}  // namespace ladarsim::apps
