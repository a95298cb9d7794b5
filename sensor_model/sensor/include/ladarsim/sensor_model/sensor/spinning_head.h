#pragma once
#include "ladarsim/sensor_model/sensor/scan_pattern.h"

namespace ladarsim::sensor_model {

/// A spinning multi-channel head (Velodyne): `channels` beams evenly spread over `field_el_deg`
/// (centres of equal cells, top first) turn clockwise seen from above, one revolution a frame; at
/// each of `steps_per_revolution` azimuth steps they fire one after another, so cell (row, column)
/// fires at (column + row / channels) / (steps_per_revolution * frame rate). Column 0 looks half a
/// step left of straight back (azimuth +180 deg), like the columns of a galvo's 360 deg field.
class SpinningHead final : public ScanPattern {
public:
    struct Parameters {
        int steps_per_revolution = 0;
        int channels = 0;
        double field_el_deg = 0.0;
        double frame_rate_hz = 0.0;
    };
    explicit SpinningHead(const Parameters& p);
    /// Throws InputError naming the key for values no such head can have.
    static std::shared_ptr<const SpinningHead> read(JsonFields& scan);

    std::string pattern() const override { return "spinning_head"; }
    int columns() const override { return p_.steps_per_revolution; }
    int rows() const override { return p_.channels; }
    RasterBeam beam(int row, int k) const override;
    double frame_rate_hz() const override { return p_.frame_rate_hz; }
    double frame_scan_duration_s() const override { return 1.0 / p_.frame_rate_hz; }
    /// The channels fire one after another within each azimuth step.
    double beam_dwell_s() const override { return frame_scan_duration_s() / (double(p_.steps_per_revolution) * p_.channels); }
    double field_az_deg() const override { return 360.0; }
    double field_el_deg() const override { return p_.field_el_deg; }
    nlohmann::json to_json() const override;

private:
    Parameters p_;
};

}  // namespace ladarsim::sensor_model
