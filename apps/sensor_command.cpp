// `ladarsim sensor show`: a bundled sensor, or the user's sensor file, and its derived quantities as JSON;
// `ladarsim sensor from-ouster`: a sensor file made from an Ouster unit's own metadata.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "command.h"
#include "ladarsim/core/json_file.h"
#include "ladarsim/dataset/dataset_directory.h"
#include "ladarsim/dataset/ouster_pcap.h"
#include "ladarsim/sensor_model/sensor/ouster_sensor.h"
#include "ladarsim/sensor_model/sensor/sensor.h"

namespace ladarsim::apps {
namespace {

struct SensorCommand {
    std::string preset = "paper_ladar";
    std::string sensor_file, metadata_file, out_file;
    bool force = false;
    CLI::App* show = nullptr;

    CLI::App* add(CLI::App& app) {
        auto* sensor = app.add_subcommand("sensor", "Sensors: the bundled presets, and sensor files made from calibrations");
        sensor->require_subcommand(1);
        show = sensor->add_subcommand("show", "Print a sensor's parameters and derived quantities as JSON: a preset, or your own sensor file");
        auto* file = show->add_option("file", sensor_file, "A sensor file (docs/sensor.md), e.g. one from-ouster wrote");
        show->add_option("--preset", preset, "Preset name")
            ->check(CLI::IsMember(sensor_model::sensor_presets()))
            ->capture_default_str()
            ->excludes(file);
        auto* ouster = sensor->add_subcommand(
            "from-ouster", "Write the sensor file of an Ouster unit from its metadata (calibration) JSON alone");
        ouster->add_option("metadata", metadata_file, "The unit's metadata file (beam angles, lidar mode, ...)")->required();
        ouster->add_option("--out", out_file, "Sensor file to write (default: print it); one ladarsim did not write only with --force");
        ouster->add_flag("--force", force, "Replace the --out file even if ladarsim did not write it");
        return sensor;
    }

    int run() {
        if (show->parsed()) {
            const sensor_model::Sensor sensor = sensor_file.empty() ? sensor_model::sensor_preset(preset)
                                                                    : sensor_model::read_sensor(read_json(sensor_file), sensor_file);
            std::cout << sensor_model::to_json(sensor).dump(2) << "\n";
            return 0;
        }
        if (!out_file.empty()) check_replaceable(out_file, "--out", force);
        const nlohmann::json sensor = sensor_model::ouster_sensor_json(read_ouster_metadata(metadata_file));
        if (out_file.empty()) {
            std::cout << sensor.dump(2) << "\n";
        } else {
            write_json(out_file, sensor);
            record_owned(out_file);
            std::printf("wrote %s (sensor \"%s\"; name it in a scenario as \"sensor\": {\"file\": ...})\n", out_file.c_str(),
                        sensor.at("name").get<std::string>().c_str());
        }
        return 0;
    }
};

}  // namespace

void add_sensor_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<SensorCommand>(), exit_code);
}

}  // namespace ladarsim::apps
