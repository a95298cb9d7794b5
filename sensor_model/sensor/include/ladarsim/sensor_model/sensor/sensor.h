#pragma once
// A sensor as its parts: the scan pattern (where and when beams fire), the transmitter, the
// receiving optics, the receiver (detector and electronics) and the gimbal. Sensors are data: a
// sensor document (JSON, docs/sensor.md) names each part's keys; the bundled ones in
// assets/sensors/ are built into the program as presets.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladarsim/core/json_fields.h"
#include "ladarsim/sensor_model/sensor/gimbal.h"
#include "ladarsim/sensor_model/sensor/optics.h"
#include "ladarsim/sensor_model/sensor/receiver.h"
#include "ladarsim/sensor_model/sensor/scan_pattern.h"
#include "ladarsim/sensor_model/sensor/transmitter.h"

namespace ladarsim::sensor_model {

struct Sensor {
    std::string name;
    std::string description;
    std::shared_ptr<const ScanPattern> scan;
    Transmitter transmitter;
    Optics optics;
    Receiver receiver;
    GimbalLimits gimbal;

    /// The frame rate of the unit as its preset or sensor file gives it; a scenario may run it
    /// slower or faster (scan.frame_rate_hz), which changes beams_per_second() but not this.
    double rated_frame_rate_hz = 0.0;

    double pulses_per_beam() const;
    double beams_per_second() const;  ///< beams per frame * frame rate
    /// Beams per frame * the rated frame rate: what "real time" means everywhere (render's
    /// summary, bench): a render at this many beams/s keeps up with the unit firing at its rate.
    double rated_beams_per_second() const;
    /// Rendered beams/s over rated_beams_per_second().
    double realtime_factor(double rendered_beams_per_s) const { return rendered_beams_per_s / rated_beams_per_second(); }
    /// Time a beam's receiver listens for one pulse: one pulse period when ranges fold, else
    /// the time of flight to max_range_m.
    double range_gate_s() const;
};

/// Names of the bundled sensors (assets/sensors/*.json).
std::vector<std::string> sensor_presets();
/// A bundled sensor's document; throws std::invalid_argument for an unknown name.
const nlohmann::json& sensor_preset_document(const std::string& name);
Sensor sensor_preset(const std::string& name);

/// A sensor document: "name", "description" (optional), and the parts "scan", "transmitter",
/// "optics", "receiver", "gimbal", every key of each required. A "derived" object (as to_json
/// writes it) is ignored: derived quantities are recomputed. Throws InputError(file, field path
/// below `path`, problem) for a missing, mistyped, out-of-range or unknown key.
Sensor read_sensor(const nlohmann::json& document, const std::string& file, const std::string& path = "");

/// The sensor of a scenario's "sensor" object: a bundled sensor by "preset" (default
/// "paper_ladar") or a sensor document by "file" (relative to `base_dir`), then any part objects
/// given beside it merged into that document key by key (RFC 7386). Reads only those keys: the
/// mount's keys are the caller's.
Sensor read_scenario_sensor(JsonFields& sensor, const std::filesystem::path& base_dir);

/// The full document, plus "derived": the quantities people check the paper's numbers with and
/// detection reads (beams_az/el, field_az/el_deg, beam_pitch_az/el_mrad, divergence_mrad ...).
nlohmann::json to_json(const Sensor& sensor);

}  // namespace ladarsim::sensor_model
