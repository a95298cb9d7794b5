// `ladarsim detect`: Algorithm 1 over a dataset, its detections (and the supervised run `eval` scores) as JSON.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <spdlog/spdlog.h>

#include "command.h"
#include "ladarsim/detect/clustering.h"
#include "option_checks.h"
#include "ladarsim/detect/sequence.h"
#include "ladarsim/dataset/dataset_directory.h"
#include "ladarsim/dataset/json_file.h"

namespace ladarsim::apps {
namespace {

struct DetectCommand {
    std::string dataset_dir, detections_file, method_name = "vrbnn";
    detect::DetectorConfig detector;
    std::uint32_t target_id = 0;
    bool force = false;
    std::vector<double> target_size{0.3, 0.3, 0.06};

    CLI::App* add(CLI::App& app) {
        auto* detect_cmd = app.add_subcommand("detect", "Run Algorithm 1 (background subtraction, (V-)RBNN, FIR or Kalman) over a dataset");
        detect_cmd->add_option("dir", dataset_dir, "Dataset directory (frames/*.pcd, background.pcd, ground_truth.json)")->required();
        detect_cmd->add_option("--method", method_name, "rbnn | vrbnn | kalman")
            ->check(CLI::IsMember({"rbnn", "vrbnn", "kalman"}))
            ->capture_default_str();
        detect_cmd->add_option("--out", detections_file, "Detections JSON (default DIR/detections-METHOD.json)");
        detect_cmd->add_flag("--force", force, "Replace the --out file even if ladarsim did not write it");
        detect_cmd->add_option("--radius", detector.rbnn_radius_m, "RBNN radius, m")
            ->check(positive_number())
            ->capture_default_str();
        detect_cmd->add_option("--lambda", detector.lambda,
                               "V-RBNN lambda (default: a radius of 1.2 of the dataset sensor's coarser beam pitch per "
                               "metre, 180 for the paper's raster; Algorithm 1's own is 7)")
            ->check(positive_number());
        detect_cmd->add_option("--bias", detector.bias_m, "V-RBNN bias, m (Algorithm 1: 0.01)")
            ->check(positive_number(true))
            ->capture_default_str();
        detect_cmd->add_option("--resolution", detector.background_resolution_m, "Background octree voxel, m")
            ->check(positive_number())
            ->capture_default_str();
        detect_cmd->add_option("--range-tolerance", detector.background_range_tolerance_m,
                               "Tracking every target, background subtraction also removes a point whose line of sight meets the "
                               "initial map within this distance, m (grazing footprints report ranges off their axis' hit)")
            ->check(positive_number(true))
            ->capture_default_str();
        detect_cmd->add_option("--min-box", detector.min_box_m, "Smallest box extent per axis, m (0: the cluster's own)")
            ->check(positive_number(true))
            ->capture_default_str();
        detect_cmd->add_option("--target-size", target_size,
                               "The sensor-aware box's size where the returns cannot resolve it, m, along the sensor's x y z "
                               "(a small quadcopter's; eval scores this box beside the one around the points)")
            ->expected(3)
            ->check(positive_number())
            ->capture_default_str();
        detect_cmd->add_option("--target", target_id, "Ground-truth id of the target to score (default: the first drone)")
            ->check(whole_number(1, std::numeric_limits<std::uint32_t>::max()));
        return detect_cmd;
    }

    int run() {
        detector.method = detect::method_from_string(method_name);
        detector.target_size_m = {target_size[0], target_size[1], target_size[2]};
        if (detections_file.empty()) detections_file = (std::filesystem::path(dataset_dir) / ("detections-" + method_name + ".json")).string();
        check_replaceable(detections_file, "--out", force);
        const detect::Sequence sequence = detect::load_sequence(dataset_dir);
        // A rendered dataset always has background.pcd (0 points: nothing static in view); only a
        // recorded one has none.
        if (!std::filesystem::exists(std::filesystem::path(dataset_dir) / "background.pcd"))
            spdlog::warn("{}: no background.pcd (a recorded dataset has no initial map): nothing is subtracted, every "
                         "return is a candidate", dataset_dir);
        else if (sequence.background.empty())
            spdlog::info("{}: background.pcd has 0 points (nothing static in view): nothing to subtract", dataset_dir);
        const nlohmann::json out = detect::detection_report(
            sequence, detector, target_id ? std::optional<std::uint32_t>(target_id) : std::nullopt);
        const auto& detections = out["detections"];
        int found = 0, predicted = 0;
        for (const auto& d : detections) {
            found += d["found"].get<bool>() && !d["predicted"].get<bool>();
            predicted += d["predicted"].get<bool>();
        }
        write_json(detections_file, out);
        record_owned(detections_file);
        std::printf("%s over %zu frames: %d detected, %d predicted, %zu without a box; wrote %s\n", method_name.c_str(),
                    detections.size(), found, predicted, detections.size() - found - predicted, detections_file.c_str());
        return 0;
    }
};

}  // namespace

void add_detect_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<DetectCommand>(), exit_code);
}

}  // namespace ladarsim::apps
