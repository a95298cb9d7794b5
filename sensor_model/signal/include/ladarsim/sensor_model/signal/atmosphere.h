#pragma once
// Clear-air extinction and daylight: what the air between sensor and target does to the beam.
#include <limits>
#include <string>

#include "ladarsim/core/json_fields.h"

namespace ladarsim::sensor_model {

/// Aerosol extinction coefficient (1/m) for a meteorological visibility (m) at a wavelength (nm),
/// Kim et al. (2001) on top of Kruse (1962):
///   alpha = (3.912 / V) * (lambda / 550 nm)^(-q),
///   q = 1.6 (V > 50 km), 1.3 (6-50 km), 0.16 V + 0.34 (1-6 km), V - 0.5 (0.5-1 km), 0 (< 0.5 km),
/// V in km inside q. An infinite visibility means no extinction.
double kim_extinction_per_m(double visibility_m, double wavelength_nm);

/// The air of a scenario (`atmosphere` in the scenario file).
struct Atmosphere {
    /// Meteorological visibility; 23 km is the "clear" standard atmosphere.
    double visibility_m = 23'000.0;
    /// Daylight adds solar background through the receiver filter; night has none.
    bool daylight = false;
    /// Solar spectral irradiance on the ground at the sensor's wavelength. 0.25 W/m^2/nm is the
    /// ASTM G173 AM1.5 global value near 1560 nm.
    double solar_irradiance_w_m2_nm = 0.25;
    /// Lambertian reflectance of what fills the receiver's field behind the target (the sunlit scene).
    double background_reflectance = 0.3;

    double extinction_per_m(double wavelength_nm) const { return kim_extinction_per_m(visibility_m, wavelength_nm); }
};

/// Reads the scenario's `atmosphere` object; unknown keys are rejected.
Atmosphere read_atmosphere(JsonFields& atmosphere);

}  // namespace ladarsim::sensor_model
