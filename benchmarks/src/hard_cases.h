#pragma once
// The cases where footprint integration is hardest (issue #17): straight edges of extended
// objects, grazing sight lines over a recorded map, the horizon, a cloud's edge and a drone at the
// edge of the footprint; each at several accuracy settings against 4096 fixed sub-rays per beam.
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladarsim/bench/benchmarks.h"
#include "ladarsim/sensor_model/render/scenario.h"

namespace ladarsim::bench {

/// Every hard case at every setting: the error against the reference and beams/s. Cases whose
/// name does not contain `only` (when not empty) are left out.
nlohmann::json hard_cases(const sensor_model::Scenario& scenario, const BenchOptions& options, const std::string& only = "");

}  // namespace ladarsim::bench
