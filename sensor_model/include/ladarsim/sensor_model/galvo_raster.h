#pragma once
#include "ladarsim/sensor_model/sensor_config.h"

namespace ladarsim::sensor_model {

/// Where and when one beam of the raster fires, relative to the gimbal's pointing and the frame start.
struct RasterBeam {
    int column = 0;              ///< 0 = leftmost beam (largest azimuth), so images read as the sensor sees
    int row = 0;                 ///< 0 = top line
    double az_offset_rad = 0.0;  ///< from the field centre, positive to the left
    double el_offset_rad = 0.0;  ///< from the field centre, positive up
    double time_offset_s = 0.0;  ///< emission time after the frame start
};

/// The galvanometer raster: `beams_el` lines of `beams_az` beams filling the field.
///
/// Angles: beam centres sit at the centres of equal cells, az = field / 2 - (column + 1/2) / beams_az
/// * field (likewise el for rows, top row first). Timing: lines follow each other from the frame
/// start, one per line duration (one galvo period for a sawtooth sweep, half a period for a
/// triangle sweep); within a line the mirror moves at constant angular rate, so beam k of the line
/// fires k * dwell after the line start, where dwell = line duration / beams_az. A sawtooth sweeps
/// every line left to right (increasing column); a triangle sweep reverses every other line. The rest of
/// the frame period after the last line is idle (gimbal settling).
///
/// A spinning head (ScanPattern::spinning) fills the same grid column by column instead: at each
/// of `beams_az` azimuth steps per revolution it fires its `beams_el` channels one after another,
/// so cell (row, column) fires at (column + row / beams_el) / (beams_az * frame rate).
class GalvoRaster {
public:
    explicit GalvoRaster(const SensorConfig& config);

    int columns() const { return columns_; }
    int rows() const { return rows_; }
    int beam_count() const { return columns_ * rows_; }
    /// The beam of raster cell (row, k): the k-th beam a galvo fires on that line, or the beam of
    /// column k of a spinning head.
    RasterBeam beam(int row, int k) const;

private:
    int columns_;
    int rows_;
    double field_az_rad_;
    double field_el_rad_;
    double line_duration_s_;
    GalvoSweep sweep_;
    ScanPattern scan_;
};

}  // namespace ladarsim::sensor_model
