// `ladarsim import-ouster`: an Ouster pcap capture and the unit's metadata decoded into a dataset
// of recorded frames whose manifest holds the unit's sensor, made from that metadata.
#include <memory>
#include <string>

#include "command.h"
#include "import_summary.h"
#include "ladarsim/dataset/dataset_directory.h"
#include "ladarsim/dataset/ouster_pcap.h"
#include "ladarsim/sensor_model/sensor/ouster_sensor.h"
#include "ladarsim/sensor_model/sensor/sensor.h"

namespace ladarsim::apps {
namespace {

struct ImportOusterCommand {
    std::string pcap_file, metadata_file, out_dir;

    CLI::App* add(CLI::App& app) {
        auto* import_cmd = app.add_subcommand(
            "import-ouster", "Decode an Ouster capture (pcap or pcapng, with the unit's metadata JSON) into a dataset of recorded frames");
        import_cmd->add_option("pcap", pcap_file, "capture of the unit's lidar packets (UDP): libpcap or pcapng, Wireshark's default")->required();
        import_cmd->add_option("--metadata", metadata_file, "The unit's metadata (calibration) JSON")->required();
        import_cmd->add_option("--out", out_dir, "Output dataset directory")->required();
        return import_cmd;
    }

    int run() {
        const OusterCalibration calibration = read_ouster_metadata(metadata_file);
        const auto frames = read_ouster_pcap(pcap_file, calibration);
        // The manifest holds the resolved sensor with its derived geometry, which detection reads.
        const sensor_model::Sensor sensor = sensor_model::read_sensor(sensor_model::ouster_sensor_json(calibration), metadata_file);
        const auto kept = write_recorded_dataset(frames, sensor_model::to_json(sensor), out_dir, pcap_file);
        print_import_summary(frames, pcap_file, out_dir, kept);
        return 0;
    }
};

}  // namespace

void add_import_ouster_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<ImportOusterCommand>(), exit_code);
}

}  // namespace ladarsim::apps
