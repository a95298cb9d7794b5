#pragma once
#include <filesystem>

#include "ladarsim/core/json_fields.h"
#include "ladarsim/scene/scene.h"
#include "ladarsim/scene/trajectory.h"

namespace ladarsim::scene {

/// Reads the scene part of a scenario file: the "objects" array and the optional "background"
/// object, from the scenario's top-level fields (which marks those keys as used; the caller reads
/// the rest and rejects unknown keys). Relative paths are resolved against `scenario_dir`.
/// Throws InputError naming the file, the field and the problem.
Scene read_scene(JsonFields& scenario, const std::filesystem::path& scenario_dir);

/// A "trajectory" object (docs/scenario.md): its "type" and that type's keys, every unknown key
/// refused. Objects and the sensor's platform (sensor.trajectory) read theirs with it.
Trajectory read_trajectory(JsonFields& trajectory);

}  // namespace ladarsim::scene
