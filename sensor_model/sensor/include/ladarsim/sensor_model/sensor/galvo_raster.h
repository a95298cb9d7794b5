#pragma once
#include "ladarsim/sensor_model/sensor/scan_pattern.h"

namespace ladarsim::sensor_model {

enum class GalvoSweep {
    sawtooth,  ///< every line sweeps in +azimuth order, one line per galvo period (fly-back not modelled)
    triangle,  ///< two lines per galvo period, alternating direction
};

/// The galvanometer raster (the paper's LADAR): `beams_el` lines of `beams_az` beams filling the field.
///
/// Angles: beam centres sit at the centres of equal cells, az = field / 2 - (column + 1/2) / beams_az
/// * field (likewise el for rows, top row first). Timing: lines follow each other from the frame
/// start, one per line duration (one galvo period for a sawtooth sweep, half a period for a
/// triangle sweep); within a line the mirror moves at constant angular rate, so beam k of the line
/// fires k * dwell after the line start, where dwell = line duration / beams_az. A sawtooth sweeps
/// every line left to right (increasing column); a triangle sweep reverses every other line. The rest of
/// the frame period after the last line is idle (gimbal settling).
class GalvoRaster final : public ScanPattern {
public:
    struct Parameters {
        double field_az_deg = 0.0;
        double field_el_deg = 0.0;
        int beams_az = 0;
        int beams_el = 0;
        double galvo_rate_hz = 0.0;
        GalvoSweep sweep = GalvoSweep::sawtooth;
        double frame_rate_hz = 0.0;
    };
    explicit GalvoRaster(const Parameters& p);
    /// Throws InputError naming the key for values no such head can have.
    static std::shared_ptr<const GalvoRaster> read(JsonFields& scan);

    const Parameters& parameters() const { return p_; }
    double line_duration_s() const;

    std::string pattern() const override { return "galvo_raster"; }
    int columns() const override { return p_.beams_az; }
    int rows() const override { return p_.beams_el; }
    RasterBeam beam(int row, int k) const override;
    double frame_rate_hz() const override { return p_.frame_rate_hz; }
    double frame_scan_duration_s() const override { return p_.beams_el * line_duration_s(); }
    double beam_dwell_s() const override { return line_duration_s() / p_.beams_az; }
    double field_az_deg() const override { return p_.field_az_deg; }
    double field_el_deg() const override { return p_.field_el_deg; }
    nlohmann::json to_json() const override;

private:
    Parameters p_;
};

}  // namespace ladarsim::sensor_model
