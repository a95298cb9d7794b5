// `ladarsim eval`: detections scored against the ground truth (L2, IoU, EAO).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "command.h"
#include "plot_script.h"
#include "ladarsim/detect/sequence.h"
#include "ladarsim/core/json_file.h"

namespace ladarsim::apps {
namespace {

struct EvalCommand {
    std::string dataset_dir, detections_file, eval_json, eval_plot;

    CLI::App* add(CLI::App& app) {
        auto* eval_cmd = app.add_subcommand("eval", "Score detections against the ground truth: L2, IoU, EAO");
        eval_cmd->add_option("dir", dataset_dir, "Dataset directory")->required();
        eval_cmd->add_option("--detections", detections_file, "Detections JSON written by `ladarsim detect`")->required();
        eval_cmd->add_option("--json", eval_json,
                             "Write the scores (mean_l2_m; mean_iou, mean_iou_bev, eao, eao_bev of the sensor-aware box and, "
                             "under point_box, of the box around the points; every target's mota, motp_m, id_switches, "
                             "ap_centre and, under tracking, the counts per class; frames, failures, per frame)");
        eval_cmd->add_option("--plot", eval_plot, "Per-frame L2 and IoU curves into this PNG (needs python3-matplotlib)");
        return eval_cmd;
    }

    int run() {
        const detect::Sequence sequence = detect::load_sequence(dataset_dir);
        const nlohmann::json scores = detect::evaluate_report(sequence, read_json(detections_file), detections_file);
        const auto& interval = scores["eao_interval"];
        const auto& points = scores["point_box"];
        std::printf("%s: %d frames, mean L2 %.3f m, %d failures, %d frames lost; EAO over lengths %d-%d\n"
                    "  sensor-aware box: mean IoU %.3f (bird's-eye %.3f), EAO %.3f (bird's-eye %.3f)\n"
                    "  box around the points: mean IoU %.3f (bird's-eye %.3f), EAO %.3f (bird's-eye %.3f)\n",
                    scores["method"].get<std::string>().c_str(), scores["frames"].get<int>(),
                    scores["mean_l2_m"].is_null() ? NAN : scores["mean_l2_m"].get<double>(), scores["failures"].get<int>(),
                    scores["frames_lost"].get<int>(), interval[0].get<int>(), interval[1].get<int>(),
                    scores["mean_iou"].get<double>(), scores["mean_iou_bev"].get<double>(), scores["eao"].get<double>(),
                    scores["eao_bev"].get<double>(), points["mean_iou"].get<double>(), points["mean_iou_bev"].get<double>(),
                    points["eao"].get<double>(), points["eao_bev"].get<double>());
        auto figure = [](const nlohmann::json& v) { return v.is_null() ? NAN : v.get<double>(); };
        const auto& tracking = scores["tracking"];
        std::printf("  every target (%d drone, bird and aircraft sightings): MOTA %.3f, MOTP %.3f m, %d ID switches, "
                    "%d misses, %d false positives; centre-distance AP %.3f\n",
                    tracking["objects"].get<int>(), figure(scores["mota"]), figure(scores["motp_m"]), scores["id_switches"].get<int>(),
                    tracking["misses"].get<int>(), tracking["false_positives"].get<int>(), figure(scores["ap_centre"]));
        if (!eval_json.empty()) write_json(eval_json, scores);
        if (!eval_plot.empty()) plot_figures("plot_eval.py", scores, eval_json, eval_plot);
        return 0;
    }
};

}  // namespace

void add_eval_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<EvalCommand>(), exit_code);
}

}  // namespace ladarsim::apps
