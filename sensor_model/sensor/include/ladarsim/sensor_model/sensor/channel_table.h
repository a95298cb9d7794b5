#pragma once
#include <vector>

#include "ladarsim/sensor_model/sensor/scan_pattern.h"

namespace ladarsim::sensor_model {

/// A spinning head whose channels point where a calibration table says (Ouster and most
/// multi-beam heads: channels neither evenly spaced nor in one vertical plane). The head turns
/// clockwise seen from above, one revolution a frame, `columns` columns a revolution; all channels
/// of a column fire together, at column / (columns * frame rate). Channel (row) r of column k points at
///   azimuth   = first_column_azimuth_deg - k * 360 / columns + azimuth_offset_deg[r]  (positive left)
///   elevation = elevation_deg[r]
/// in the sensor frame (field centre at azimuth and elevation 0).
class ChannelTable final : public ScanPattern {
public:
    struct Parameters {
        int columns = 0;
        double frame_rate_hz = 0.0;
        double first_column_azimuth_deg = 0.0;
        std::vector<double> elevation_deg;
        std::vector<double> azimuth_offset_deg;
    };
    explicit ChannelTable(Parameters p);
    /// Throws InputError naming the key for values no such head can have.
    static std::shared_ptr<const ChannelTable> read(JsonFields& scan);

    std::string pattern() const override { return "channel_table"; }
    int columns() const override { return p_.columns; }
    int rows() const override { return static_cast<int>(p_.elevation_deg.size()); }
    RasterBeam beam(int row, int k) const override;
    double frame_rate_hz() const override { return p_.frame_rate_hz; }
    double frame_scan_duration_s() const override { return 1.0 / p_.frame_rate_hz; }
    /// A column's channels fire together: each beam position is held for one column's time.
    double beam_dwell_s() const override { return frame_scan_duration_s() / p_.columns; }
    double field_az_deg() const override { return 360.0; }
    /// The channels' elevation span plus one mean spacing, so that pitch_el_rad is that spacing.
    double field_el_deg() const override;
    nlohmann::json to_json() const override;

private:
    Parameters p_;
};

}  // namespace ladarsim::sensor_model
