// `ladarsim train-classifier`: the track classifier (birds, drones, aircraft, clutter) trained on
// the tracks the detector follows in a rendered campaign.
#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "command.h"
#include "detector_options.h"
#include "ladarsim/core/input_error.h"
#include "ladarsim/core/json_file.h"
#include "ladarsim/dataset/dataset_directory.h"
#include "ladarsim/detect/sequence.h"
#include "ladarsim/detect/track_classification.h"

namespace ladarsim::apps {
namespace {

struct TrainClassifierCommand {
    std::vector<std::string> campaign_dirs;
    std::string model_file;
    std::vector<std::string> splits{"train"};
    DetectorOptions options;
    detect::ClassifierTraining training;
    bool force = false;

    CLI::App* add(CLI::App& app) {
        auto* cmd = app.add_subcommand("train-classifier",
                                       "Train the track classifier (drone, bird, plane, clutter) on a rendered campaign's tracks");
        cmd->add_option("campaign", campaign_dirs, "Campaign directories (`ladarsim campaign --out`), trained on together")->required();
        cmd->add_option("--out", model_file, "Model file to write (XGBoost JSON)")->required();
        cmd->add_option("--split", splits, "Splits to train on (default train)")->check(CLI::IsMember({"train", "val", "test"}));
        cmd->add_option("--rounds", training.rounds, "Boosting rounds")->check(CLI::Range(1, 10000));
        cmd->add_flag("--force", force, "Replace the --out file even if ladarsim did not write it");
        options.add(*cmd);
        return cmd;
    }

    int run() {
        check_replaceable(model_file, "--out", force);
        std::vector<detect::TrackFeatures> features;
        std::vector<std::size_t> labels;
        int used = 0;
        for (const std::string& campaign_dir : campaign_dirs) {
            const std::filesystem::path dir(campaign_dir);
            const std::filesystem::path index_file = dir / "campaign.json";
            const nlohmann::json index = read_json(index_file);
            if (!index.contains("sequences") || !index["sequences"].is_array())
                throw InputError(index_file.string(), "sequences", "missing: not a finished campaign (`ladarsim campaign` writes it last)");
            for (const auto& entry : index["sequences"]) {
                const std::string split = entry.value("split", "");
                if (std::find(splits.begin(), splits.end(), split) == splits.end()) continue;
                const detect::Sequence s = detect::load_sequence(dir / entry.at("directory").get<std::string>());
                detect::add_training_rows(s, options.config(), features, labels);
                ++used;
            }
        }
        if (features.empty())
            throw InputError(campaign_dirs.front(), "sequences", "no tracks in the " + std::to_string(used) + " sequences of the chosen splits to train on");
        std::array<int, detect::kTrackClassCount> per_class{};
        for (std::size_t l : labels) ++per_class[l];
        const detect::TrackClassifier model = detect::TrackClassifier::train(features, labels, training);
        model.save(model_file);
        record_owned(model_file);
        std::printf("trained on %zu rows from %d sequences (", features.size(), used);
        for (std::size_t c = 0; c < detect::kTrackClassCount; ++c)
            std::printf("%s%s %d", c ? ", " : "", std::string(detect::track_class_names()[c]).c_str(), per_class[c]);
        std::printf("); wrote %s\n", model_file.c_str());
        // What the model learnt from: the features by their share of its gain.
        const auto importance = model.feature_importance();
        std::vector<std::size_t> order(importance.size());
        for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
        std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return importance[a] > importance[b]; });
        std::printf("features by share of the gain:");
        for (std::size_t k : order) std::printf(" %s %.3f", std::string(detect::track_feature_names()[k]).c_str(), importance[k]);
        std::printf("\n");
        return 0;
    }
};

}  // namespace

void add_train_classifier_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<TrainClassifierCommand>(), exit_code);
}

}  // namespace ladarsim::apps
