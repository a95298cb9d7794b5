// `ladarsim eval`: the boxes of a detections file scored against the ground truth, and nothing
// else: no score is read from the file and no detector is run in its place (`benchmark` runs one).
#include <memory>
#include <string>

#include "command.h"
#include "ladarsim/core/json_file.h"
#include "ladarsim/detect/scoring.h"
#include "score_report.h"

namespace ladarsim::apps {
namespace {

struct EvalCommand {
    std::string dataset_dir, detections_file, eval_json, eval_plot;
    bool force = false;

    CLI::App* add(CLI::App& app) {
        auto* eval_cmd = app.add_subcommand(
            "eval",
            "Score the boxes of a detections file (`ladarsim detect`'s, or any detector's in its format: docs/detection.md) "
            "against the ground truth: L2, IoU without resets, and with tracks CLEAR MOT and AP. EAO needs the tracker in "
            "the loop: `ladarsim benchmark`");
        eval_cmd->add_option("dir", dataset_dir, "Dataset directory")->required();
        eval_cmd->add_option("--detections", detections_file,
                             "Detections JSON: one entry per frame, matched by its \"frame\"; any order")
            ->required();
        eval_cmd->add_option("--json", eval_json,
                             "Write the scores (measures: which the file supports; mean_l2_m; mean_iou, mean_iou_bev of the "
                             "sensor-aware box and, under point_box, of the box around the points; frames_lost; success, "
                             "precision; with tracks every target's mota, motp_m, id_switches, ap_centre (ground plane), "
                             "ap_centre_3d and, under tracking, the counts per class; per frame)");
        eval_cmd->add_option("--plot", eval_plot, "Per-frame L2 and IoU curves into this PNG (needs python3-matplotlib)");
        eval_cmd->add_flag("--force", force, "Replace the --json and --plot files even if ladarsim did not write them");
        return eval_cmd;
    }

    int run() {
        check_score_outputs(eval_json, eval_plot, force);
        const detect::Sequence sequence = detect::load_sequence(dataset_dir);
        report_scores(detect::evaluate_report(sequence, read_json(detections_file), detections_file), eval_json, eval_plot);
        return 0;
    }
};

}  // namespace

void add_eval_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<EvalCommand>(), exit_code);
}

}  // namespace ladarsim::apps
