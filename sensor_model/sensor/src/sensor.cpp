#include "ladarsim/sensor_model/sensor/sensor.h"

#include <algorithm>
#include <map>
#include <numbers>
#include <stdexcept>

#include "ladarsim/core/json_file.h"
#include "ladarsim/sensor_model/sensor/physical_constants.h"
#include "ladarsim/core/units.h"

namespace ladarsim::sensor_model {

// Generated from assets/sensors/*.json (embed_sensor_presets.cmake): file stem -> document text.
const std::map<std::string, std::string>& sensor_preset_texts();

namespace {

constexpr const char* kParts[] = {"scan", "transmitter", "optics", "receiver", "gimbal"};

const std::map<std::string, nlohmann::json>& preset_documents() {
    static const std::map<std::string, nlohmann::json> documents = [] {
        std::map<std::string, nlohmann::json> out;
        for (const auto& [name, text] : sensor_preset_texts()) out.emplace(name, nlohmann::json::parse(text));
        return out;
    }();
    return documents;
}

template <typename Part>
Part read_part(JsonFields& top, const char* key, const std::string& file) {
    JsonFields fields(top.object(key), file, top.path_of(key));
    Part part = Part::read(fields);
    fields.reject_unknown_keys();
    return part;
}

}  // namespace

double Sensor::pulses_per_beam() const { return transmitter.pulse_rate_hz * scan->beam_dwell_s(); }
double Sensor::beams_per_second() const { return double(scan->columns()) * scan->rows() * scan->frame_rate_hz(); }
double Sensor::rated_beams_per_second() const {
    return double(scan->columns()) * scan->rows() * (rated_frame_rate_hz > 0.0 ? rated_frame_rate_hz : scan->frame_rate_hz());
}
double Sensor::range_gate_s() const {
    return receiver.range_folding ? 1.0 / transmitter.pulse_rate_hz : 2.0 * receiver.max_range_m / kSpeedOfLight_mps;
}

std::vector<std::string> sensor_presets() {
    std::vector<std::string> names;
    for (const auto& [name, document] : preset_documents()) names.push_back(name);
    return names;
}

const nlohmann::json& sensor_preset_document(const std::string& name) {
    const auto it = preset_documents().find(name);
    if (it == preset_documents().end()) {
        std::string names;
        for (const auto& n : sensor_presets()) names += (names.empty() ? "" : ", ") + n;
        throw std::invalid_argument("unknown sensor preset \"" + name + "\"; the presets are " + names);
    }
    return it->second;
}

Sensor sensor_preset(const std::string& name) {
    return read_sensor(sensor_preset_document(name), "assets/sensors/" + name + ".json");
}

Sensor read_sensor(const nlohmann::json& document, const std::string& file, const std::string& path) {
    JsonFields top(document, file, path);
    Sensor s;
    s.name = top.string("name");
    s.description = top.string("description", "");
    {
        JsonFields scan(top.object("scan"), file, top.path_of("scan"));
        s.scan = read_scan_pattern(scan);
        scan.reject_unknown_keys();
    }
    s.transmitter = read_part<Transmitter>(top, "transmitter", file);
    s.optics = read_part<Optics>(top, "optics", file);
    s.receiver = read_part<Receiver>(top, "receiver", file);
    s.gimbal = read_part<GimbalLimits>(top, "gimbal", file);
    if (top.has("derived")) top.object("derived");
    top.reject_unknown_keys();
    s.rated_frame_rate_hz = s.scan->frame_rate_hz();
    return s;
}

Sensor read_scenario_sensor(JsonFields& sensor, const std::filesystem::path& base_dir) {
    nlohmann::json document;
    if (sensor.has("file")) {
        if (sensor.has("preset")) sensor.fail("file", "names a sensor file beside \"preset\"; give one of them");
        const std::filesystem::path file = base_dir / sensor.string("file");
        document = read_json(file);
        read_sensor(document, file.string());  // its own errors name its own file
    } else {
        document = sensor_preset_document(sensor.choice("preset", sensor_presets(), "paper_ladar"));
    }
    const double rated_frame_rate_hz = document.at("scan").at("frame_rate_hz").get<double>();
    for (const char* part : kParts) {
        if (!sensor.has(part)) continue;
        const nlohmann::json& changes = sensor.object(part);
        document[part].merge_patch(changes);
    }
    Sensor s = read_sensor(document, sensor.file(), "sensor");
    s.rated_frame_rate_hz = rated_frame_rate_hz;
    return s;
}

nlohmann::json to_json(const Sensor& s) {
    const ScanPattern& scan = *s.scan;
    return {
        {"name", s.name},
        {"description", s.description},
        {"scan", scan.to_json()},
        {"transmitter", s.transmitter.to_json()},
        {"optics", s.optics.to_json()},
        {"receiver", s.receiver.to_json()},
        {"gimbal", s.gimbal.to_json()},
        {"derived",
         {{"beams_az", scan.columns()},
          {"beams_el", scan.rows()},
          {"field_az_deg", scan.field_az_rad() / kDeg},
          {"field_el_deg", scan.field_el_rad() / kDeg},
          {"beam_pitch_az_mrad", scan.pitch_az_rad() * 1e3},
          {"beam_pitch_el_mrad", scan.pitch_el_rad() * 1e3},
          {"divergence_mrad", std::max(s.transmitter.divergence_mrad, s.transmitter.divergence_el_mrad)},
          {"frame_scan_duration_s", scan.frame_scan_duration_s()},
          {"beam_dwell_s", scan.beam_dwell_s()},
          {"pulses_per_beam", s.pulses_per_beam()},
          {"unambiguous_range_m", s.transmitter.unambiguous_range_m()},
          {"beams_per_second", s.beams_per_second()},
          {"rated_beams_per_second", s.rated_beams_per_second()},
          {"pulse_energy_j", s.transmitter.pulse_energy_j()},
          {"average_power_w", s.transmitter.average_power_w()},
          {"range_gate_s", s.range_gate_s()}}},
    };
}

}  // namespace ladarsim::sensor_model
