#pragma once
// A campaign spec (docs/campaign.md): how many sequences of how many frames, and the
// distributions each sequence's scenario is drawn from: sensor, weather, objects, background map,
// splits and the campaign seed. Reading checks every key and every distribution up front.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladarsim/campaign/distribution.h"

namespace ladarsim::campaign {

/// The trajectory types a group of objects may draw (docs/scenario.md's, but keyframes).
inline const std::vector<std::string> kTrajectoryTypes = {"fixed", "approach", "straight", "winding", "hover"};

/// One entry of "objects": `count` objects of one class and model, each drawing its own size,
/// place and motion.
struct ObjectGroup {
    std::string path;          ///< "objects[2]": names its draws and its errors
    std::string object_class;  ///< a scenario class: drone, bird, plane, building, terrain, tree, cloud
    std::string model;         ///< as the spec gives it
    std::filesystem::path model_file;  ///< absolute
    Distribution count;
    std::optional<Distribution> size_m, reflectance;
    /// A fog or cloud volume: mor_m, or extinction_per_km with backscatter_per_km_sr.
    std::optional<Distribution> mor_m, extinction_per_km, backscatter_per_km_sr;
    /// Where each starts: `range_m` horizontally from the sensor at `bearing_deg` (from +x, east,
    /// towards +y), `altitude_m` above z = 0.
    Distribution range_m, bearing_deg, altitude_m;
    Distribution trajectory;  ///< one of kTrajectoryTypes
    /// The keys of the trajectory types it can draw (absent where none needs it).
    std::optional<Distribution> speed_mps, heading_deg, amplitude_m, period_s, radius_m;
};

/// One recorded map a sequence may stand before.
struct BackgroundChoice {
    std::string file;                  ///< as the spec gives it
    std::filesystem::path map_file;    ///< absolute
    std::vector<Distribution> offset_m;  ///< x, y, z
    Distribution heading_deg;
    nlohmann::json fixed_keys;         ///< the scenario's other background keys, passed on as given
};

struct CampaignSpec {
    std::filesystem::path file;       ///< the spec file
    nlohmann::json source;            ///< as read, with --sequences and --frames applied
    int sequences = 0;
    int frames = 0;
    std::uint64_t seed = 1;
    /// Shares of train, val and test (summing to 1).
    double train = 1.0, val = 0.0, test = 0.0;
    /// Sensor entries (a scenario's "sensor" without position_m and cue_object), fixed or a choice.
    Distribution sensor;
    Distribution sensor_height_m;
    nlohmann::json render;            ///< passed to every scenario (frames and seed set per sequence)
    /// Atmosphere keys given, each a distribution: visibility_km, daylight,
    /// solar_irradiance_w_m2_nm, background_reflectance.
    std::vector<std::pair<std::string, Distribution>> atmosphere;
    std::vector<ObjectGroup> groups;
    double background_probability = 0.0;
    /// The maps, in the order of background_choice's values.
    std::vector<BackgroundChoice> backgrounds;
    Distribution background_choice;
};

/// Overrides of the spec from the command line.
struct SpecOverrides {
    std::optional<int> sequences, frames;
    std::optional<std::uint64_t> seed;
};

/// Reads and checks a spec file. Throws InputError naming the file, the key (e.g.
/// "objects[1].range_m.uniform") and the problem: an unknown key, a value or distribution bound
/// outside what the key allows, lo above hi, empty choices, bad weights, shares not summing to 1,
/// a sensor entry the scenario reader refuses, a missing model or map file.
CampaignSpec read_campaign_spec(const std::filesystem::path& file, const SpecOverrides& overrides = {});

}  // namespace ladarsim::campaign
