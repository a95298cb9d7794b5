#include "score_report.h"

#include <cmath>
#include <cstdio>
#include <map>

#include "ladarsim/core/json_file.h"
#include "plot_script.h"

namespace ladarsim::apps {

namespace {

double figure(const nlohmann::json& v) { return v.is_null() ? NAN : v.get<double>(); }

/// The measures scoring.h names, in words.
std::string measures_in_words(const nlohmann::json& measures) {
    static const std::map<std::string, std::string> words = {{"average_overlap", "average overlap without resets"},
                                                             {"l2", "L2"},
                                                             {"mot", "CLEAR MOT"},
                                                             {"ap", "centre-distance AP"},
                                                             {"eao", "EAO (supervised, VOT resets)"}};
    std::string out;
    for (const auto& m : measures) out += (out.empty() ? "" : ", ") + words.at(m.get<std::string>());
    return out;
}

}  // namespace

void report_scores(const nlohmann::json& scores, const std::string& json_path, const std::string& plot_path) {
    const std::string method = scores["method"].get<std::string>();
    const auto& points = scores["point_box"];
    std::printf("%s: %d frames, mean L2 %.3f m, %d frames lost (no overlap in 3-D)\n"
                "  sensor-aware box: mean IoU %.3f (bird's-eye %.3f)\n"
                "  box around the points: mean IoU %.3f (bird's-eye %.3f)\n",
                method.empty() ? "detections" : method.c_str(), scores["frames"].get<int>(), figure(scores["mean_l2_m"]),
                scores["frames_lost"].get<int>(), scores["mean_iou"].get<double>(), scores["mean_iou_bev"].get<double>(),
                points["mean_iou"].get<double>(), points["mean_iou_bev"].get<double>());
    if (scores.contains("tracking")) {
        const auto& tracking = scores["tracking"];
        std::printf("  every target (%d drone, bird and aircraft sightings): MOTA %.3f, MOTP %.3f m, %d ID switches, "
                    "%d misses, %d false positives; centre-distance AP %.3f on the ground plane (%.3f in 3-D)\n",
                    tracking["objects"].get<int>(), figure(scores["mota"]), figure(scores["motp_m"]), scores["id_switches"].get<int>(),
                    tracking["misses"].get<int>(), tracking["false_positives"].get<int>(), figure(scores["ap_centre"]),
                    figure(scores["ap_centre_3d"]));
    }
    if (scores.contains("eao")) {
        const auto& interval = scores["eao_interval"];
        std::printf("  supervised (re-initialised 5 frames after each failure), EAO over lengths %d-%d: sensor-aware box EAO %.3f "
                    "(bird's-eye %.3f), %d failures; box around the points EAO %.3f (bird's-eye %.3f)\n",
                    interval[0].get<int>(), interval[1].get<int>(), scores["eao"].get<double>(), scores["eao_bev"].get<double>(),
                    scores["failures"].get<int>(), points["eao"].get<double>(), points["eao_bev"].get<double>());
    }
    std::printf("  scores: %s", measures_in_words(scores["measures"]).c_str());
    if (!scores.contains("eao"))
        std::printf(" (the file supports these; EAO needs the tracker in the loop: `ladarsim benchmark DIR --method M`%s)",
                    scores.contains("ignored") ? ", and the file's supervised block is ignored" : "");
    std::printf("\n");
    if (!json_path.empty()) write_json(json_path, scores);
    if (!plot_path.empty()) plot_figures("plot_eval.py", scores, json_path, plot_path);
}

}  // namespace ladarsim::apps
