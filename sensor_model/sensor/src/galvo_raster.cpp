#include "ladarsim/sensor_model/sensor/galvo_raster.h"

#include <numbers>

#include "frame_period_check.h"

namespace ladarsim::sensor_model {

GalvoRaster::GalvoRaster(const Parameters& p) : p_(p) {}

std::shared_ptr<const GalvoRaster> GalvoRaster::read(JsonFields& scan) {
    Parameters p;
    // A galvo mirror cannot sweep further than a half turn.
    p.field_az_deg = scan.number("field_az_deg", 1e-4, 180.0);
    p.field_el_deg = scan.number("field_el_deg", 1e-4, 180.0);
    p.beams_az = static_cast<int>(scan.integer("beams_az", 1, 65535));
    p.beams_el = static_cast<int>(scan.integer("beams_el", 1, 65535));
    p.galvo_rate_hz = scan.number("galvo_rate_hz", 1e-3, 1e7);
    p.sweep = scan.choice("sweep", {"sawtooth", "triangle"}, "sawtooth") == "sawtooth" ? GalvoSweep::sawtooth
                                                                                    : GalvoSweep::triangle;
    p.frame_rate_hz = scan.number("frame_rate_hz", 1e-3, 1e4);
    auto raster = std::make_shared<GalvoRaster>(p);
    check_frame_period(*raster, scan);
    return raster;
}

double GalvoRaster::line_duration_s() const {
    return p_.sweep == GalvoSweep::sawtooth ? 1.0 / p_.galvo_rate_hz : 0.5 / p_.galvo_rate_hz;
}

RasterBeam GalvoRaster::beam(int row, int step) const {
    RasterBeam b;
    b.row = row;
    const bool reversed = p_.sweep == GalvoSweep::triangle && b.row % 2 == 1;
    b.column = reversed ? p_.beams_az - 1 - step : step;
    b.az_offset_rad = cell_centre_rad(b.column, p_.beams_az, field_az_rad());
    b.el_offset_rad = cell_centre_rad(b.row, p_.beams_el, field_el_rad());
    b.time_offset_s = line_duration_s() * (b.row + static_cast<double>(step) / p_.beams_az);
    return b;
}

nlohmann::json GalvoRaster::to_json() const {
    return {{"pattern", pattern()},
            {"field_az_deg", p_.field_az_deg},
            {"field_el_deg", p_.field_el_deg},
            {"beams_az", p_.beams_az},
            {"beams_el", p_.beams_el},
            {"galvo_rate_hz", p_.galvo_rate_hz},
            {"sweep", p_.sweep == GalvoSweep::sawtooth ? "sawtooth" : "triangle"},
            {"frame_rate_hz", p_.frame_rate_hz}};
}

}  // namespace ladarsim::sensor_model
