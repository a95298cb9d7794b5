// `ladarsim detect`: Algorithm 1 over a dataset, its detections and tracks as JSON (what `eval` scores).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <spdlog/spdlog.h>

#include "command.h"
#include "data_dir.h"
#include "detector_options.h"
#include "ladarsim/detect/sequence.h"
#include "ladarsim/core/json_file.h"
#include "ladarsim/dataset/dataset_directory.h"

namespace ladarsim::apps {
namespace {

struct DetectCommand {
    std::string dataset_dir, detections_file, classifier_file;
    DetectorOptions options;
    bool force = false;

    CLI::App* add(CLI::App& app) {
        auto* detect_cmd = app.add_subcommand(
            "detect", "Run Algorithm 1 (background subtraction, (V-)RBNN, FIR or Kalman) over a dataset and write its boxes "
                      "(scored by eval; `benchmark` also scores EAO, with the tracker in the loop)");
        detect_cmd->add_option("dir", dataset_dir, "Dataset directory (frames/*.pcd, background.pcd, ground_truth.json)")->required();
        options.add(*detect_cmd);
        detect_cmd->add_option("--out", detections_file, "Detections JSON (default DIR/detections-METHOD.json)");
        detect_cmd->add_flag("--force", force, "Replace the --out file even if ladarsim did not write it");
        detect_cmd->add_option("--classifier", classifier_file,
                               "Track classifier (`ladarsim train-classifier`) giving each track a class and class_confidence "
                               "(default: the bundled one, classifiers/track_classes.json in ladarsim's data; none: no classes)");
        return detect_cmd;
    }

    int run() {
        if (detections_file.empty())
            detections_file = (std::filesystem::path(dataset_dir) / ("detections-" + options.method_name + ".json")).string();
        check_replaceable(detections_file, "--out", force);
        const detect::Sequence sequence = detect::load_sequence(dataset_dir);
        // A rendered dataset always has background.pcd (0 points: nothing static in view); only a
        // recorded one has none.
        if (!std::filesystem::exists(std::filesystem::path(dataset_dir) / "background.pcd"))
            spdlog::warn("{}: no background.pcd (a recorded dataset has no initial map): nothing is subtracted, every "
                         "return is a candidate", dataset_dir);
        else if (sequence.background.empty())
            spdlog::info("{}: background.pcd has 0 points (nothing static in view): nothing to subtract", dataset_dir);
        std::optional<detect::TrackClassifier> classifier;
        if (classifier_file.empty()) classifier_file = data_file("classifiers/track_classes.json").string();
        if (classifier_file != "none") classifier.emplace(detect::TrackClassifier::load(classifier_file));
        const nlohmann::json out =
            detect::detection_report(sequence, options.config(), options.target(), classifier ? &*classifier : nullptr);
        const auto& detections = out["detections"];
        int found = 0, predicted = 0;
        for (const auto& d : detections) {
            found += d["found"].get<bool>() && !d["predicted"].get<bool>();
            predicted += d["predicted"].get<bool>();
        }
        write_json(detections_file, out);
        record_owned(detections_file);
        std::printf("%s over %zu frames: %d detected, %d predicted, %zu without a box; wrote %s\n", options.method_name.c_str(),
                    detections.size(), found, predicted, detections.size() - found - predicted, detections_file.c_str());
        return 0;
    }
};

}  // namespace

void add_detect_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<DetectCommand>(), exit_code);
}

}  // namespace ladarsim::apps
