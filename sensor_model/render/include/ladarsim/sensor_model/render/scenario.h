#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "ladarsim/scene/scene.h"
#include "ladarsim/sensor_model/signal/atmosphere.h"
#include "ladarsim/sensor_model/sensor/sensor.h"

namespace ladarsim::sensor_model {

/// Where the sensor stands and how its gimbal starts.
struct SensorMount {
    Eigen::Vector3d position_world = Eigen::Vector3d::Zero();
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< world_from_sensor rotation
    /// Initial pointing of the field centre in the sensor frame; when absent and a cue object is
    /// set, the gimbal starts on the cue (the radar has already handed the target over).
    std::optional<double> gimbal_az_deg;
    std::optional<double> gimbal_el_deg;
    /// Object whose true position cues the gimbal (a radar track); 0 = no cue, the gimbal holds.
    std::uint32_t cue_object_id = 0;

    Eigen::Isometry3d world_from_sensor() const;
};

struct RenderSettings {
    int frames = 20;
    std::uint64_t seed = 1;
    double start_time_s = 0.0;
    int motion_steps = 2;        ///< Embree time steps per moving object per frame
    bool jitter = true;          ///< jitter sub-rays within their footprint cells
    /// Speckle, detector noise, timing jitter and false alarms. Off: every return is its noise-free
    /// expectation, still subject to the detection threshold (for checking against closed forms).
    bool noise = true;
    /// 0: adaptive footprints to `footprint_tolerance`; N > 0: N stratified sub-rays per beam
    /// (brute force, the reference the adaptive integration is checked against).
    int footprint_samples = 0;
    /// With footprint_samples > 0, a footprint over a recorded map is integrated along this many
    /// lines instead (the map's converged reference, its rays for other objects spread over the
    /// lines); 0: the sub-rays there too.
    int footprint_map_lines = 0;
    /// Relative error allowed on each object's echo energy per beam (adaptive footprints).
    double footprint_tolerance = 0.05;
    double footprint_truncation = 1.5;   ///< sub-rays lie within this many 1/e^2 radii
    /// Write each frame's full waveforms (waveforms/NNNNNN.h5): every beam is then detected in its
    /// sampled waveform, one meeting a single surface too (see BeamReceiver::receive).
    bool waveforms = false;
};

/// Everything one run needs, read from a scenario file: the single source of truth of a dataset.
struct Scenario {
    std::filesystem::path file;
    scene::Scene scene;
    Sensor sensor;
    SensorMount mount;
    RenderSettings render;
    Atmosphere atmosphere;
    /// The file as read, for the manifest.
    nlohmann::json source;
};

/// Reads and validates a scenario file. Throws InputError naming the file, the field and the problem.
Scenario load_scenario(const std::filesystem::path& file);

/// The name a scenario held in memory goes by, in place of a file name: Python's own term for what
/// is not a file ("<string>", "<stdin>"), and the argument's, `scenario`.
inline constexpr const char* kInMemoryScenarioName = "<scenario dict>";

/// The same for a scenario document held in memory (from Python): `extends` and relative paths
/// are resolved against `base_dir`, as they would be for a file in that folder. The scenario's
/// `file`, and the file errors name, is `base_dir/<scenario dict>`.
Scenario load_scenario(const nlohmann::json& document, const std::filesystem::path& base_dir);

}  // namespace ladarsim::sensor_model
