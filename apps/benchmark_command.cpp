// `ladarsim benchmark`: a named detector run over a dataset and scored as it runs, the tracker in
// the loop: everything `eval` scores of its boxes, plus VOT's supervised EAO, which no file can
// carry (a file's claims cannot be checked without re-running its tracker).
#include <memory>
#include <string>

#include "command.h"
#include "detector_options.h"
#include "ladarsim/detect/scoring.h"
#include "score_report.h"

namespace ladarsim::apps {
namespace {

struct BenchmarkCommand {
    std::string dataset_dir, scores_json, scores_plot;
    DetectorOptions options;
    bool force = false;

    CLI::App* add(CLI::App& app) {
        auto* cmd = app.add_subcommand("benchmark",
                                       "Run a detector (Algorithm 1) over a dataset and score it as it runs: what eval scores, "
                                       "plus EAO under VOT's supervised protocol (re-initialised on the ground truth after failures)");
        cmd->add_option("dir", dataset_dir, "Dataset directory with ground_truth.json")->required();
        options.add(*cmd);
        cmd->add_option("--json", scores_json,
                        "Write the scores: eval's (see `ladarsim eval --help`) plus eao, eao_bev, eao_interval, failures (and "
                        "the same under point_box), per frame supervised_iou and initialised");
        cmd->add_option("--plot", scores_plot, "Per-frame L2 and IoU curves into this PNG (needs python3-matplotlib)");
        cmd->add_flag("--force", force, "Replace the --json and --plot files even if ladarsim did not write them");
        return cmd;
    }

    int run() {
        check_score_outputs(scores_json, scores_plot, force);
        const detect::Sequence sequence = detect::load_sequence(dataset_dir);
        report_scores(detect::benchmark_report(sequence, options.config(), options.target()), scores_json, scores_plot);
        return 0;
    }
};

}  // namespace

void add_benchmark_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<BenchmarkCommand>(), exit_code);
}

}  // namespace ladarsim::apps
