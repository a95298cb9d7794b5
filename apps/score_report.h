#pragma once
// What `eval` and `benchmark` print and write of their scores (ladarsim/detect/scoring.h).
#include <string>

#include <nlohmann/json.hpp>

namespace ladarsim::apps {

/// Before any work: refuses (InputError naming --json or --plot) to replace a file at `json_path`
/// or `plot_path` that ladarsim did not write, unless `force` (check_replaceable).
void check_score_outputs(const std::string& json_path, const std::string& plot_path, bool force);

/// Prints `scores` on stdout: the target's one-pass scores, every target's when there are tracks,
/// EAO when the tracker ran in the loop, and which measures the scores cover; a figure there is
/// none of is said so, never "nan". Writes them to `json_path` and draws them into `plot_path`
/// (scripts/plot_eval.py) when given, each listed as ladarsim's (record_owned).
void report_scores(const nlohmann::json& scores, const std::string& json_path, const std::string& plot_path);

}  // namespace ladarsim::apps
