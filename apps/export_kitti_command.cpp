// `ladarsim export-kitti`: a dataset in the KITTI object-detection layout, for detectors that read KITTI.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "command.h"
#include "ladarsim/campaign/campaign_index.h"
#include "ladarsim/dataset/kitti_export.h"
#include "progress.h"

namespace ladarsim::apps {
namespace {

struct ExportKittiCommand {
    std::string dataset_dir, out_dir;
    KittiExportOptions options;

    CLI::App* add(CLI::App& app) {
        auto* export_cmd = app.add_subcommand(
            "export-kitti",
            "Write a dataset in the KITTI object-detection layout: training/velodyne/NNNNNN.bin (float32 x y z "
            "intensity, the sensor frame, intensity / the dataset's largest), training/label_2 (drones, birds and "
            "planes with returns, boxes from ground truth grown to hold their returns), training/calib (no camera: the standard axis "
            "permutation), ladarsim_export.json (source, frame numbers, class map); see docs/kitti.md");
        export_cmd->add_option("dir", dataset_dir,
                               "Dataset directory (frames/*.pcd, manifest.json, ground_truth.json if any), or a campaign's "
                               "(campaign.json): every sequence, with ImageSets/train.txt, val.txt and test.txt from its splits")
            ->required();
        export_cmd->add_option("--out", out_dir,
                               "Export directory: absent, empty or an earlier export (files of yours in it are kept)")
            ->required();
        export_cmd->add_flag("--exact-boxes", options.exact_boxes,
                             "Label boxes are ground truth's exactly, not grown to hold the object's returns (which lie on "
                             "beam axes, up to half a footprint beside it); ladarsim_export.json keeps the exact boxes either way");
        return export_cmd;
    }

    int run() {
        const ExportProgress progress{progress_lines("intensity scan, frame"), progress_lines("export, frame")};
        // A campaign's sequences go into one export, its splits into ImageSets.
        std::vector<KittiSource> sources;
        if (campaign::is_campaign(dataset_dir))
            for (const auto& sequence : campaign::read_campaign_index(dataset_dir)) sources.push_back({sequence.directory, sequence.split});
        const KittiExportSummary s = sources.empty() ? export_kitti(dataset_dir, out_dir, options, progress)
                                                     : export_kitti(dataset_dir, sources, out_dir, options, progress);
        std::printf("exported %d frames, %llu returns, %llu labels from %s into %s (KITTI layout, intensity / %g)\n",
                    s.frames, static_cast<unsigned long long>(s.returns), static_cast<unsigned long long>(s.labels),
                    dataset_dir.c_str(), s.out.c_str(), static_cast<double>(s.intensity_scale));
        if (!sources.empty())
            std::printf("the campaign's %zu sequences in one export; its splits in ImageSets/train.txt, val.txt and test.txt\n",
                        sources.size());
        if (!s.kept.empty()) std::printf("%s\n", kept_files_note(s.kept, s.out).c_str());
        return 0;
    }
};

}  // namespace

void add_export_kitti_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<ExportKittiCommand>(), exit_code);
}

}  // namespace ladarsim::apps
