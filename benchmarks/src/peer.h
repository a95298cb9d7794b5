#pragma once
#include <nlohmann/json.hpp>

#include "ladarsim/bench/benchmarks.h"
#include "ladarsim/sensor_model/render/scenario.h"

namespace ladarsim::bench {

/// The scene peers time themselves on: a flat plane and a sphere, the scenario's sensor aimed at
/// the sphere, 19 fixed sub-rays per pulse (HELIOS++'s default beam sampling) and the adaptive
/// default, on every core: pulses (beams) per second and returns per pulse, to set beside a peer's
/// figures on the same scene.
nlohmann::json peer_scene(const sensor_model::Scenario& scenario, const BenchOptions& options);

}  // namespace ladarsim::bench
