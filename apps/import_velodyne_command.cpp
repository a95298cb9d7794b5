// `ladarsim import-velodyne`: a VLP-16 pcap capture decoded into a dataset of recorded frames.
#include <memory>
#include <string>

#include "command.h"
#include "import_summary.h"
#include "ladarsim/dataset/dataset_directory.h"
#include "ladarsim/dataset/velodyne_pcap.h"
#include "ladarsim/sensor_model/sensor/sensor.h"

namespace ladarsim::apps {
namespace {

struct ImportVelodyneCommand {
    std::string pcap_file, out_dir;

    CLI::App* add(CLI::App& app) {
        auto* import_cmd = app.add_subcommand("import-velodyne", "Decode a VLP-16 capture (pcap or pcapng) into a dataset of recorded frames");
        import_cmd->add_option("pcap", pcap_file, "capture of VLP-16 packets: libpcap or pcapng, Wireshark's default")->required();
        import_cmd->add_option("--out", out_dir, "Output dataset directory")->required();
        return import_cmd;
    }

    int run() {
        const auto frames = read_velodyne_vlp16_pcap(pcap_file);
        // The manifest names the sensor, so that detection takes the VLP-16's geometry.
        const auto kept = write_recorded_dataset(frames, sensor_model::to_json(sensor_model::sensor_preset("velodyne_vlp16")), out_dir, pcap_file);
        print_import_summary(frames, pcap_file, out_dir, kept);
        return 0;
    }
};

}  // namespace

void add_import_velodyne_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<ImportVelodyneCommand>(), exit_code);
}

}  // namespace ladarsim::apps
