#include "ladarsim/sensor_model/sensor/spinning_head.h"

#include <numbers>


namespace ladarsim::sensor_model {

SpinningHead::SpinningHead(const Parameters& p) : p_(p) {}

std::shared_ptr<const SpinningHead> SpinningHead::read(JsonFields& scan) {
    Parameters p;
    p.steps_per_revolution = static_cast<int>(scan.integer("steps_per_revolution", 1, 65535));
    p.channels = static_cast<int>(scan.integer("channels", 1, 65535));
    p.field_el_deg = scan.number("field_el_deg", 1e-4, 180.0);
    p.frame_rate_hz = scan.number("frame_rate_hz", 1e-3, 1e4);
    return std::make_shared<SpinningHead>(p);
}

RasterBeam SpinningHead::beam(int row, int step) const {
    RasterBeam b;
    b.row = row;
    b.column = step;
    b.az_offset_rad = cell_centre_rad(b.column, p_.steps_per_revolution, field_az_rad());
    b.el_offset_rad = cell_centre_rad(b.row, p_.channels, field_el_rad());
    b.time_offset_s = frame_scan_duration_s() * (step + static_cast<double>(row) / p_.channels) / p_.steps_per_revolution;
    return b;
}

nlohmann::json SpinningHead::to_json() const {
    return {{"pattern", pattern()},
            {"steps_per_revolution", p_.steps_per_revolution},
            {"channels", p_.channels},
            {"field_el_deg", p_.field_el_deg},
            {"frame_rate_hz", p_.frame_rate_hz}};
}

}  // namespace ladarsim::sensor_model
