#pragma once
#include <nlohmann/json.hpp>

#include "ladarsim/bench/benchmarks.h"
#include "ladarsim/sensor_model/render/scenario.h"

namespace ladarsim::bench {

/// How cost grows: with beams per frame (expect linear), triangles (expect logarithmic) and
/// background map points (time and memory).
nlohmann::json scaling(const sensor_model::Scenario& scenario, const BenchOptions& options);

}  // namespace ladarsim::bench
