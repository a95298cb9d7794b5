#pragma once
// A dataset's frames as LAS 1.4 files, as surveying and GIS tools read them:
//   NNNNNN.las            one per frame (the i-th frame in name order is i), point format 6
//   ladarsim_export.json  where it came from, the frame, the time base, the intensity scale and
//                         the class map
// Each return is one point: its position (the sensor frame, or the world's), intensity scaled to
// 16 bits by the dataset's largest, return number and number of returns of its beam, GPS time
// (the return's time_s), a classification from its object's class (las_class_code), its source
// (surface, volume, false alarm) in user data, the beam's azimuth as scan angle, and two extra-bytes
// fields: object_id (uint32, no_data 0xFFFFFFFF: a false alarm) and intensity_pe (float32, the
// intensity unscaled). docs/las.md says what each field holds and why.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ladarsim/dataset/dataset_directory.h"
#include "ladarsim/dataset/intensity_scale.h"
#include "ladarsim/dataset/frame.h"

namespace ladarsim {

/// The ASPRS classification of a return: 7 (noise) for a false alarm; else by its object's class
/// `object_class`: "terrain" 2 (ground), "tree" 5 (high vegetation), "building" 6, "background"
/// (the recorded map, which holds ground and buildings alike) 1 (unclassified), and the
/// user-definable codes (64 and above) for what ASPRS has no class for: "drone" 64, "bird" 65,
/// "plane" 66, "cloud" 67; any other class 1; std::nullopt (no ground truth: a recording) 0
/// (never classified).
std::uint8_t las_class_code(ReturnSource source, const std::optional<std::string>& object_class);

/// The class map las_class_code applies, for the export's record: class name -> code.
const std::vector<std::pair<std::string, int>>& las_class_map();

/// The export's directory layout: own entries NNNNNN.las and ladarsim_export.json.
const OutputLayout& las_layout();

struct LasExportOptions {
    /// Points in world coordinates, not the sensor frame: a fixed mount's pose from manifest.json, a
    /// moving platform's at each return's own time from sensor_trajectory.txt.
    bool world = false;
};

struct LasExportSummary {
    std::filesystem::path out;      ///< the export directory as written (see checked_output_dir)
    int frames = 0;
    std::uint64_t returns = 0;
    float intensity_scale = 1.0f;   ///< LAS intensity = round(65535 x intensity / this), 0 when negative
    std::vector<std::string> kept;  ///< the user's entries kept in `out` (see swap_in_output)
};

/// Writes dataset `dataset_dir` (frames/*.pcd, manifest.json, ground_truth.json when present) into
/// `out_dir` as LAS files. Staged and swapped in as a dataset is (checked_output_dir,
/// swap_in_output). Throws InputError naming the file and the problem for a missing directory,
/// manifest or frames, a malformed file, or `world` asked of a dataset whose manifest has no mount
/// (a recording).
LasExportSummary export_las(const std::filesystem::path& dataset_dir, const std::filesystem::path& out_dir,
                            const LasExportOptions& options = {}, const ExportProgress& progress = {});

}  // namespace ladarsim
