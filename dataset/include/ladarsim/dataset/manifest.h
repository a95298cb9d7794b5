#pragma once
// A dataset's manifest.json, written for every dataset by write_manifest, rendered or recorded:
//   software  {"name", "version"} of the program that wrote it
//   sensor    the sensor's parameters, with "derived": {"beams_az", "beams_el", "field_az_deg",
//             "field_el_deg", "divergence_mrad", ...}, which readers (detection, the viewer) size
//             their work by
//   frames    one record per frame: "index", "start_time_s", "end_time_s", "returns"; a render's
//             also the gimbal's pointing ("gimbal_az_rad", "gimbal_el_rad") and its timing
// and what made it: a render's "scenario_file", "scenario", "mount", "render", "threads",
// "processes" and "totals"; a recording's "recorded_from".
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace ladarsim {

/// The raster a frame was scanned with, as detection sizes its clustering and its boxes by it.
struct SensorGeometry {
    int beams_az = 0;              ///< beams per line (columns)
    int beams_el = 0;              ///< lines per frame (rows)
    double field_az_deg = 0.0;     ///< full field of the raster in azimuth
    double field_el_deg = 0.0;
    double divergence_mrad = 0.0;  ///< full angle at the 1/e^2 irradiance radius, the wider axis
};

/// Gimbal pointing (of the field centre) at a frame's start, radians, sensor frame.
struct FramePointing {
    double gimbal_az_rad = 0.0;
    double gimbal_el_rad = 0.0;
};

struct Manifest {
    /// Which dataset this is: a 64-bit FNV-1a hash of the manifest file's bytes, in hex. Every
    /// render and import writes a manifest of its own (time, frames, sensor), so results computed on
    /// one dataset can be told from another's.
    std::string id;
    SensorGeometry sensor;
    /// Per frame, in the manifest's order; empty where the frame records none (recorded frames).
    std::vector<std::optional<FramePointing>> pointing;
};

/// Reads `sensor.derived` and `frames` of a manifest.json; keys it does not need are ignored.
/// Throws InputError naming the file and the field for a missing file, a manifest without
/// `sensor.derived` (the field named in both cases), or a missing or mistyped value.
Manifest read_manifest(const std::filesystem::path& file);

/// The "software" record of a manifest: this program's name and version.
nlohmann::json software_json();

/// What a manifest holds besides its software record (see the top of this file).
struct ManifestRecord {
    nlohmann::json sensor;
    nlohmann::json frames = nlohmann::json::array();
    nlohmann::json origin = nlohmann::json::object();  ///< what made the dataset: its keys, as above
};

/// Writes `file` (atomically) with the software record and `record`'s keys.
void write_manifest(const std::filesystem::path& file, const ManifestRecord& record);

}  // namespace ladarsim
