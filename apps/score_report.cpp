#include "score_report.h"

#include <cstdio>
#include <map>
#include <string>

#include "ladarsim/core/json_file.h"
#include "ladarsim/dataset/dataset_directory.h"
#include "plot_script.h"

namespace ladarsim::apps {

namespace {

/// `v` to three decimals and `unit`, or `none` (saying why there is no figure) when it is null:
/// never "nan".
std::string figure(const nlohmann::json& v, const std::string& unit, const std::string& none) {
    if (v.is_null()) return none;
    char text[32];
    std::snprintf(text, sizeof text, "%.3f", v.get<double>());
    return text + unit;
}

/// The measures scoring.h names, in words.
std::string measures_in_words(const nlohmann::json& measures) {
    static const std::map<std::string, std::string> words = {{"average_overlap", "average overlap without resets"},
                                                             {"l2", "L2"},
                                                             {"mot", "CLEAR MOT"},
                                                             {"ap", "centre-distance AP"},
                                                             {"eao", "EAO (supervised, VOT resets)"},
                                                             {"classification", "track classes"}};
    std::string out;
    for (const auto& m : measures) out += (out.empty() ? "" : ", ") + words.at(m.get<std::string>());
    return out;
}

}  // namespace

void check_score_outputs(const std::string& json_path, const std::string& plot_path, bool force) {
    if (!json_path.empty()) check_replaceable(json_path, "--json", force);
    if (!plot_path.empty()) check_replaceable(plot_path, "--plot", force);
}

void report_scores(const nlohmann::json& scores, const std::string& json_path, const std::string& plot_path) {
    const std::string method = scores["method"].get<std::string>();
    const auto& points = scores["point_box"];
    const std::string l2 = scores["mean_l2_m"].is_null() ? "no mean L2 (the target was detected in no frame)"
                                                         : "mean L2 " + figure(scores["mean_l2_m"], " m", "");
    std::printf("%s: %d frames, %s, %d frames lost (no overlap in 3-D)\n"
                "  sensor-aware box: mean IoU %.3f (bird's-eye %.3f)\n"
                "  box around the points: mean IoU %.3f (bird's-eye %.3f)\n",
                method.empty() ? "detections" : method.c_str(), scores["frames"].get<int>(),
                l2.c_str(),
                scores["frames_lost"].get<int>(), scores["mean_iou"].get<double>(), scores["mean_iou_bev"].get<double>(),
                points["mean_iou"].get<double>(), points["mean_iou_bev"].get<double>());
    if (scores.contains("tracking") && scores["mota"].is_null()) {
        std::printf("  every target: nothing to score (no drone, bird or aircraft sighting in the ground truth)\n");
    } else if (scores.contains("tracking")) {
        const auto& tracking = scores["tracking"];
        std::printf("  every target (%d drone, bird and aircraft sightings): MOTA %.3f, MOTP %s, %d ID switches, "
                    "%d misses, %d false positives; centre-distance AP %s on the ground plane (%s in 3-D)\n",
                    tracking["objects"].get<int>(), scores["mota"].get<double>(),
                    figure(scores["motp_m"], " m", "none (nothing matched)").c_str(), scores["id_switches"].get<int>(),
                    tracking["misses"].get<int>(), tracking["false_positives"].get<int>(),
                    figure(scores["ap_centre"], "", "none (no track)").c_str(),
                    figure(scores["ap_centre_3d"], "", "none").c_str());
    }
    if (scores.contains("classification")) {
        const auto& c = scores["classification"];
        const auto& drone = c["per_class"]["drone"];
        int unclassified = 0;
        for (const auto& [name, n] : c["unclassified"].items()) unclassified += n.get<int>();
        const auto& settle = c["frames_to_settle"];
        std::printf("  track classes (%d tracks, %d too short for a class): drone precision %s, recall %s; %d bird tracks called "
                    "drones; class settled after %s frames on average\n",
                    c["tracks"].get<int>(), unclassified, figure(drone["precision"], "", "none").c_str(),
                    figure(drone["recall"], "", "none").c_str(), c["confusion"]["bird"]["drone"].get<int>(),
                    figure(settle.is_null() ? settle : settle["mean"], "", "no").c_str());
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
    if (!json_path.empty()) {
        write_json(json_path, scores);
        record_owned(json_path);
    }
    if (!plot_path.empty()) {
        plot_figures("plot_eval.py", scores, json_path, plot_path);
        record_owned(plot_path);
    }
}

}  // namespace ladarsim::apps
