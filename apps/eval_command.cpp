// `ladarsim eval`: detections scored against the ground truth (L2, IoU, EAO).
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "command.h"
#include "plot_script.h"
#include "ladarsim/detect/sequence.h"
#include "ladarsim/dataset/dataset_directory.h"
#include "ladarsim/dataset/json_file.h"

namespace ladarsim::apps {
namespace {

std::string fixed(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3f", value);
    return text;
}

struct EvalCommand {
    std::string dataset_dir, detections_file, eval_json, eval_plot;
    bool force = false;

    CLI::App* add(CLI::App& app) {
        auto* eval_cmd = app.add_subcommand("eval", "Score detections against the ground truth: L2, IoU, EAO");
        eval_cmd->add_option("dir", dataset_dir, "Dataset directory")->required();
        eval_cmd->add_option("--detections", detections_file, "Detections JSON written by `ladarsim detect`")->required();
        eval_cmd->add_option("--json", eval_json,
                             "Write the scores (mean_l2_m; mean_iou, mean_iou_bev, eao, eao_bev of the sensor-aware box and, "
                             "under point_box, of the box around the points; every target's mota, motp_m, id_switches, "
                             "ap_centre and, under tracking, the counts per class; frames, failures, per frame)");
        eval_cmd->add_option("--plot", eval_plot, "Per-frame L2 and IoU curves into this PNG (needs python3-matplotlib)");
        eval_cmd->add_flag("--force", force, "Replace the --json and --plot files even if ladarsim did not write them");
        return eval_cmd;
    }

    int run() {
        if (!eval_json.empty()) check_replaceable(eval_json, "--json", force);
        if (!eval_plot.empty()) check_replaceable(eval_plot, "--plot", force);
        const detect::Sequence sequence = detect::load_sequence(dataset_dir);
        const nlohmann::json scores = detect::evaluate_report(sequence, read_json(detections_file), detections_file);
        const auto& interval = scores["eao_interval"];
        const auto& points = scores["point_box"];
        const std::string l2 = scores["mean_l2_m"].is_null() ? "no mean L2 (the target was detected in no frame)"
                                                             : "mean L2 " + fixed(scores["mean_l2_m"].get<double>()) + " m";
        std::printf("%s: %d frames, %s, %d failures, %d frames lost; EAO over lengths %d-%d\n"
                    "  sensor-aware box: mean IoU %.3f (bird's-eye %.3f), EAO %.3f (bird's-eye %.3f)\n"
                    "  box around the points: mean IoU %.3f (bird's-eye %.3f), EAO %.3f (bird's-eye %.3f)\n",
                    scores["method"].get<std::string>().c_str(), scores["frames"].get<int>(), l2.c_str(),
                    scores["failures"].get<int>(), scores["frames_lost"].get<int>(), interval[0].get<int>(), interval[1].get<int>(),
                    scores["mean_iou"].get<double>(), scores["mean_iou_bev"].get<double>(), scores["eao"].get<double>(),
                    scores["eao_bev"].get<double>(), points["mean_iou"].get<double>(), points["mean_iou_bev"].get<double>(),
                    points["eao"].get<double>(), points["eao_bev"].get<double>());
        const auto& tracking = scores["tracking"];
        if (scores["mota"].is_null()) {
            std::printf("  every target: nothing to score (no drone, bird or aircraft sighting in the ground truth)\n");
        } else {
            const std::string ap = scores["ap_centre"].is_null() ? "none (no track)" : fixed(scores["ap_centre"].get<double>());
            const std::string motp = scores["motp_m"].is_null() ? "none (nothing matched)" : fixed(scores["motp_m"].get<double>()) + " m";
            std::printf("  every target (%d drone, bird and aircraft sightings): MOTA %.3f, MOTP %s, %d ID switches, "
                        "%d misses, %d false positives; centre-distance AP %s\n",
                        tracking["objects"].get<int>(), scores["mota"].get<double>(), motp.c_str(),
                        scores["id_switches"].get<int>(), tracking["misses"].get<int>(), tracking["false_positives"].get<int>(),
                        ap.c_str());
        }
        if (!eval_json.empty()) {
            write_json(eval_json, scores);
            record_owned(eval_json);
        }
        if (!eval_plot.empty()) {
            // The plot script reads the scores from a file: without --json, a temporary one of ours.
            const std::filesystem::path json_path =
                !eval_json.empty() ? std::filesystem::path(eval_json)
                                   : std::filesystem::temp_directory_path() / ("ladarsim-eval-" + std::to_string(::getpid()) + ".json");
            if (eval_json.empty()) write_json(json_path, scores);
            try {
                run_plot_script("plot_eval.py", json_path.string(), eval_plot);
            } catch (...) {
                if (eval_json.empty()) std::filesystem::remove(json_path);
                throw;
            }
            if (eval_json.empty()) std::filesystem::remove(json_path);
            record_owned(eval_plot);
        }
        return 0;
    }
};

}  // namespace

void add_eval_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<EvalCommand>(), exit_code);
}

}  // namespace ladarsim::apps
