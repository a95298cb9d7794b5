#include "ladarsim/sensor_model/sensor/optics.h"

#include <numbers>

namespace ladarsim::sensor_model {

double Optics::aperture_area_m2() const { return std::numbers::pi / 4.0 * aperture_diameter_m * aperture_diameter_m; }

Optics Optics::read(JsonFields& o) {
    Optics x;
    x.aperture_diameter_m = o.number("aperture_diameter_m", 1e-4, 10.0);
    x.optics_efficiency = o.number("optics_efficiency", 1e-6, 1.0);
    x.receiver_fov_mrad = o.number("receiver_fov_mrad", 1e-3, 1e3);
    x.filter_width_nm = o.number("filter_width_nm", 1e-3, 1e3);
    return x;
}

nlohmann::json Optics::to_json() const {
    return {{"aperture_diameter_m", aperture_diameter_m},
            {"optics_efficiency", optics_efficiency},
            {"receiver_fov_mrad", receiver_fov_mrad},
            {"filter_width_nm", filter_width_nm}};
}

}  // namespace ladarsim::sensor_model
