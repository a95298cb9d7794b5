#pragma once
// What `eval` and `benchmark` print and write of their scores (ladarsim/detect/scoring.h).
#include <string>

#include <nlohmann/json.hpp>

namespace ladarsim::apps {

/// Prints `scores` on stdout: the target's one-pass scores, every target's when there are tracks,
/// EAO when the tracker ran in the loop, and which measures the scores cover. Writes them to
/// `json_path` and draws them into `plot_path` (scripts/plot_eval.py) when given.
void report_scores(const nlohmann::json& scores, const std::string& json_path, const std::string& plot_path);

}  // namespace ladarsim::apps
