// `ladarsim export-las`: a dataset's frames as LAS 1.4 files, for surveying and GIS tools.
#include <cstdio>
#include <memory>
#include <string>

#include "command.h"
#include "ladarsim/dataset/las_export.h"
#include "progress.h"

namespace ladarsim::apps {
namespace {

struct ExportLasCommand {
    std::string dataset_dir, out_dir;
    LasExportOptions options;

    CLI::App* add(CLI::App& app) {
        auto* export_cmd = app.add_subcommand(
            "export-las",
            "Write a dataset's frames as LAS 1.4 files: OUT/NNNNNN.las per frame (point format 6: return number and "
            "count, intensity / the dataset's largest in 16 bits, GPS time = the return's time_s, ASPRS classification "
            "from the object's class, drones/birds/planes/clouds 64-67; extra bytes object_id and intensity_pe), the "
            "sensor frame unless --world, and ladarsim_export.json (source, time base, class map); see docs/las.md");
        export_cmd->add_option("dir", dataset_dir, "Dataset directory (frames/*.pcd, manifest.json, ground_truth.json if any)")
            ->required();
        export_cmd->add_option("--out", out_dir, "Export directory: absent, empty or an earlier export (files of yours in it are kept)")
            ->required();
        export_cmd->add_flag("--world", options.world,
                             "Points in world coordinates (ENU metres, placed by the mount's pose in manifest.json), not "
                             "the sensor frame");
        return export_cmd;
    }

    int run() {
        const ExportProgress progress{progress_lines("intensity scan, frame"), progress_lines("export, frame")};
        const LasExportSummary s = export_las(dataset_dir, out_dir, options, progress);
        std::printf("exported %d frames, %llu returns from %s into %s (LAS 1.4, %s frame, intensity x 65535 / %g)\n", s.frames,
                    static_cast<unsigned long long>(s.returns), dataset_dir.c_str(), s.out.c_str(),
                    options.world ? "world" : "sensor", static_cast<double>(s.intensity_scale));
        if (!s.kept.empty()) std::printf("%s\n", kept_files_note(s.kept, s.out).c_str());
        return 0;
    }
};

}  // namespace

void add_export_las_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<ExportLasCommand>(), exit_code);
}

}  // namespace ladarsim::apps
