#include "ladarsim/sensor_model/signal/atmosphere.h"

#include <cmath>

namespace ladarsim::sensor_model {

double kim_extinction_per_m(double visibility_m, double wavelength_nm) {
    if (std::isinf(visibility_m)) return 0.0;
    const double v_km = visibility_m / 1000.0;
    double q = 0.0;
    if (v_km > 50.0) q = 1.6;
    else if (v_km > 6.0) q = 1.3;
    else if (v_km > 1.0) q = 0.16 * v_km + 0.34;
    else if (v_km > 0.5) q = v_km - 0.5;
    return 3.912 / visibility_m * std::pow(wavelength_nm / 550.0, -q);
}

Atmosphere read_atmosphere(JsonFields& f) {
    Atmosphere a;
    a.visibility_m = 1000.0 * f.number("visibility_km", 0.01, 1e6, a.visibility_m / 1000.0);
    a.daylight = f.boolean("daylight", a.daylight);
    a.solar_irradiance_w_m2_nm = f.number("solar_irradiance_w_m2_nm", 0.0, 10.0, a.solar_irradiance_w_m2_nm);
    a.background_reflectance = f.number("background_reflectance", 0.0, 1.0, a.background_reflectance);
    f.reject_unknown_keys();
    return a;
}

}  // namespace ladarsim::sensor_model
