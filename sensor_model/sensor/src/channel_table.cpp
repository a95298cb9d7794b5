#include "ladarsim/sensor_model/sensor/channel_table.h"

#include <algorithm>
#include <numbers>
#include "ladarsim/core/units.h"


namespace ladarsim::sensor_model {

namespace {

std::vector<double> angles(JsonFields& scan, const std::string& key, double limit_deg) {
    const nlohmann::json& list = scan.array(key);
    std::vector<double> out;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string where = key + "[" + std::to_string(i) + "]";
        if (!list[i].is_number()) scan.fail(where, "must be a number");
        const double a = list[i].get<double>();
        if (!(a >= -limit_deg && a <= limit_deg))
            scan.fail(where, "must be within +-" + std::to_string(static_cast<int>(limit_deg)) + " deg");
        out.push_back(a);
    }
    return out;
}
}  // namespace

ChannelTable::ChannelTable(Parameters p) : p_(std::move(p)) {}

std::shared_ptr<const ChannelTable> ChannelTable::read(JsonFields& scan) {
    Parameters p;
    p.columns = static_cast<int>(scan.integer("columns", 1, 65535));
    p.frame_rate_hz = scan.number("frame_rate_hz", 1e-3, 1e4);
    p.first_column_azimuth_deg = scan.number("first_column_azimuth_deg", -360.0, 360.0);
    p.elevation_deg = angles(scan, "elevation_deg", 90.0);
    p.azimuth_offset_deg = angles(scan, "azimuth_offset_deg", 180.0);
    if (p.elevation_deg.size() < 2) scan.fail("elevation_deg", "needs at least two channels");
    if (p.azimuth_offset_deg.size() != p.elevation_deg.size())
        scan.fail("azimuth_offset_deg", "has " + std::to_string(p.azimuth_offset_deg.size()) +
                                            " channels, elevation_deg has " + std::to_string(p.elevation_deg.size()));
    return std::make_shared<ChannelTable>(std::move(p));
}

RasterBeam ChannelTable::beam(int row, int step) const {
    RasterBeam b;
    b.row = row;
    b.column = step;
    const std::size_t r = static_cast<std::size_t>(row);
    b.az_offset_rad = (p_.first_column_azimuth_deg - step * 360.0 / p_.columns + p_.azimuth_offset_deg[r]) * kDeg;
    b.el_offset_rad = p_.elevation_deg[r] * kDeg;
    b.time_offset_s = frame_scan_duration_s() * step / p_.columns;
    return b;
}

double ChannelTable::field_el_deg() const {
    const auto [lo, hi] = std::minmax_element(p_.elevation_deg.begin(), p_.elevation_deg.end());
    return rows() > 1 ? (*hi - *lo) * rows() / (rows() - 1) : 0.0;
}

nlohmann::json ChannelTable::to_json() const {
    return {{"pattern", pattern()},
            {"columns", p_.columns},
            {"frame_rate_hz", p_.frame_rate_hz},
            {"first_column_azimuth_deg", p_.first_column_azimuth_deg},
            {"elevation_deg", p_.elevation_deg},
            {"azimuth_offset_deg", p_.azimuth_offset_deg}};
}

}  // namespace ladarsim::sensor_model
