// `ladarsim import-velodyne`: a VLP-16 pcap capture decoded into a dataset of recorded frames.
#include <cstddef>
#include <cstdio>
#include <memory>
#include <string>

#include "command.h"
#include "ladarsim/sensor_model/dataset.h"
#include "ladarsim/sensor_model/velodyne_pcap.h"

namespace ladarsim::apps {
namespace {

struct ImportVelodyneCommand {
    std::string pcap_file, out_dir;

    CLI::App* add(CLI::App& app) {
        auto* import_cmd = app.add_subcommand("import-velodyne", "Decode a VLP-16 pcap capture into a dataset of recorded frames");
        import_cmd->add_option("pcap", pcap_file, "libpcap capture of VLP-16 packets")->required();
        import_cmd->add_option("--out", out_dir, "Output dataset directory")->required();
        return import_cmd;
    }

    int run() {
        const auto frames = sensor_model::read_velodyne_vlp16_pcap(pcap_file);
        sensor_model::write_recorded_dataset(frames, out_dir, pcap_file);
        std::size_t returns = 0;
        for (const auto& f : frames) returns += f.returns.size();
        std::printf("decoded %zu frames, %zu returns from %s into %s/frames\n", frames.size(), returns, pcap_file.c_str(),
                    out_dir.c_str());
        return 0;
    }
};

}  // namespace

void add_import_velodyne_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<ImportVelodyneCommand>(), exit_code);
}

}  // namespace ladarsim::apps
