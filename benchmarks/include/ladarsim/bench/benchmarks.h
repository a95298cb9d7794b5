#pragma once
// `ladarsim bench`: what ladarsim's speed and accuracy are on this machine, measured as ratios
// and errors within one run (machines are noisy; ratios and errors are not).
#include <filesystem>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

namespace ladarsim::bench {

struct BenchOptions {
    std::filesystem::path scenario = "assets/scenarios/default.json";
    /// A scenario over a recorded map, for speed against error there (skipped, with the reason,
    /// when it cannot be loaded, e.g. without ../shared/data).
    std::filesystem::path map_scenario = "assets/scenarios/dataset2-autzen.json";
    bool quick = false;  ///< fewer frames and sizes: about a minute
    /// When set, only the hard cases whose name contains it are run (nothing else).
    std::string hard_case;
    std::function<void(const std::string&)> progress = [](const std::string&) {};
};

/// Runs every benchmark and returns their figures. Top-level keys: pipeline_vs_raw_embree,
/// realtime_factor, count_error_pct, and the details under pipeline, realtime, accuracy,
/// recorded_map, scaling, hard_cases. Real time is the scenario's sensor firing at its rated beam
/// rate (Sensor::rated_beams_per_second, as render's summary says it; the default scenario's
/// 150 x 20 beams at 20 frames/s: 60,000 beams/s).
nlohmann::json run_benchmarks(const BenchOptions& options);

}  // namespace ladarsim::bench
