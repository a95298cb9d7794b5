#include "ladarsim/dataset/manifest.h"

#include <cstdint>
#include <cstdio>
#include <fstream>

#include <limits>
#include <string>

#include "ladarsim/core/input_error.h"
#include "ladarsim/core/json_fields.h"
#include "ladarsim/core/json_file.h"

namespace ladarsim {

namespace {

constexpr double kAnyNumber = std::numeric_limits<double>::max();

SensorGeometry read_geometry(JsonFields& manifest) {
    const std::string problem = "missing: the dataset does not say which sensor took it";
    if (!manifest.has("sensor")) manifest.fail("sensor.derived", problem);
    JsonFields sensor(manifest.object("sensor"), manifest.file(), "sensor");
    if (!sensor.has("derived")) sensor.fail("derived", problem);
    JsonFields derived(sensor.object("derived"), manifest.file(), sensor.path_of("derived"));
    SensorGeometry g;
    g.beams_az = static_cast<int>(derived.integer("beams_az", 1, 65535));
    g.beams_el = static_cast<int>(derived.integer("beams_el", 1, 65535));
    g.field_az_deg = derived.number("field_az_deg", 1e-4, 360.0);
    g.field_el_deg = derived.number("field_el_deg", 1e-4, 360.0);
    g.divergence_mrad = derived.number("divergence_mrad", 1e-4, 100.0);
    return g;
}

std::optional<FramePointing> read_pointing(const nlohmann::json& frame, const std::string& file,
                                           const std::string& path) {
    JsonFields f(frame, file, path);
    if (!f.has("gimbal_az_rad")) return std::nullopt;
    FramePointing p;
    p.gimbal_az_rad = f.number("gimbal_az_rad", -kAnyNumber, kAnyNumber);
    p.gimbal_el_rad = f.number("gimbal_el_rad", -kAnyNumber, kAnyNumber);
    return p;
}

}  // namespace

namespace {
std::string file_id(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::uint64_t hash = 14695981039346656037ull;  // FNV-1a, 64 bits
    for (char c; in.get(c);) hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ull;
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
    return hex;
}
}  // namespace

Manifest read_manifest(const std::filesystem::path& file) {
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) {
        throw InputError(file.string(), "sensor.derived",
                         "no manifest.json: the dataset does not say which sensor took it");
    }
    const nlohmann::json json = read_json(file);
    JsonFields top(json, file.string(), "");
    Manifest m;
    m.id = file_id(file);
    m.sensor = read_geometry(top);
    const auto& frames = top.array("frames");
    for (std::size_t i = 0; i < frames.size(); ++i) {
        m.pointing.push_back(read_pointing(frames[i], file.string(), "frames[" + std::to_string(i) + "]"));
    }
    return m;
}

nlohmann::json software_json() { return {{"name", "ladarsim"}, {"version", LADARSIM_VERSION}}; }

void write_manifest(const std::filesystem::path& file, const ManifestRecord& record) {
    nlohmann::json manifest = record.origin;
    manifest["software"] = software_json();
    manifest["sensor"] = record.sensor;
    manifest["frames"] = record.frames;
    write_json(file, manifest);
}

}  // namespace ladarsim
