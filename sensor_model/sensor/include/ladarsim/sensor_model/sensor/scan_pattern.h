#pragma once
// How a sensor's beams fill a frame: which direction each raster cell points at and when it fires.
// Every pattern lays its beams on a grid of columns x rows (the range image's pixels), fires each
// cell once per frame, and describes itself as the "scan" part of a sensor document.
#include <memory>
#include <numbers>
#include <string>

#include <nlohmann/json.hpp>

#include "ladarsim/core/json_fields.h"

namespace ladarsim::sensor_model {

/// Where and when one beam fires, relative to the gimbal's pointing and the frame start.
struct RasterBeam {
    int column = 0;              ///< 0 = leftmost beam (largest azimuth), so images read as the sensor sees
    int row = 0;                 ///< 0 = top line
    double az_offset_rad = 0.0;  ///< from the field centre, positive to the left
    double el_offset_rad = 0.0;  ///< from the field centre, positive up
    double time_offset_s = 0.0;  ///< emission time after the frame start
};

/// The centre of cell `index` of `count` equal cells across a field of `field_rad`, from the
/// field's centre, cell 0 at the positive end (left, or top).
inline double cell_centre_rad(int index, int count, double field_rad) { return (0.5 - (index + 0.5) / count) * field_rad; }

class ScanPattern {
public:
    virtual ~ScanPattern() = default;

    /// The document's "pattern" key: "galvo_raster", "spinning_head", "channel_table".
    virtual std::string pattern() const = 0;
    virtual int columns() const = 0;
    virtual int rows() const = 0;
    int beam_count() const { return columns() * rows(); }
    /// The k-th beam the pattern fires on row `row` (a galvo line), or column k of a spinning head.
    virtual RasterBeam beam(int row, int k) const = 0;

    virtual double frame_rate_hz() const = 0;
    /// Time from the first beam of a frame to the end of its last beam's slot.
    virtual double frame_scan_duration_s() const = 0;
    /// Time each beam position is held: the pulses of one beam are those fired within it.
    virtual double beam_dwell_s() const = 0;
    /// Angular extent of the grid (beam centres plus one pitch) and the spacing of neighbouring
    /// beams (the mean spacing where it varies).
    virtual double field_az_deg() const = 0;
    virtual double field_el_deg() const = 0;
    double field_az_rad() const { return field_az_deg() * std::numbers::pi / 180.0; }
    double field_el_rad() const { return field_el_deg() * std::numbers::pi / 180.0; }
    double pitch_az_rad() const { return field_az_rad() / columns(); }
    double pitch_el_rad() const { return field_el_rad() / rows(); }

    /// The "scan" part of a sensor document, "pattern" included; read_scan_pattern reads it back.
    virtual nlohmann::json to_json() const = 0;
};

/// The scan part of a sensor document, by its "pattern". Throws InputError naming the field.
std::shared_ptr<const ScanPattern> read_scan_pattern(JsonFields& scan);

}  // namespace ladarsim::sensor_model
