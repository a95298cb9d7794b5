#pragma once
// The monostatic Lambertian range equation, per sub-ray. Summed over a beam's sub-rays it gives
// the extended-target law (1/R^2, target filling the footprint) and the point-target law (1/R^4,
// target smaller than the footprint, through the fraction of sub-rays that hit it) without a
// switch between them.
#include <cmath>
#include <numbers>

namespace ladarsim::sensor_model {

/// Energy reaching the detector from one sub-ray (J):
///   E = E_pulse * w * eta * T^2 * rho * cos(theta) * r_a^2 / (R^2 + r_a^2),
/// w the sub-ray's share of the pulse energy, eta the optics efficiency, T the one-way
/// transmission, rho the diffuse reflectance, theta the incidence angle, r_a the aperture radius.
/// The last factor is the view factor from a small Lambertian patch to a coaxial disc: it is the
/// familiar A_r / (pi R^2) once R >> r_a, and stays below 1 as R -> 0, so no return can carry
/// more energy than the pulse.
inline double lambertian_echo_energy_j(double pulse_energy_j, double weight, double optics_efficiency,
                                       double two_way_transmission, double reflectance, double cos_incidence,
                                       double aperture_area_m2, double range_m) {
    const double r2 = aperture_area_m2 / std::numbers::pi;
    return pulse_energy_j * weight * optics_efficiency * two_way_transmission * reflectance * cos_incidence * r2 /
           (range_m * range_m + r2);
}

/// Number of speckle cells averaged by the aperture, M = 1 + (D_r * D_spot / (lambda R))^2: the
/// aperture area over the area of one speckle (lambda R / D_spot across). The received energy of a
/// rough target fluctuates as Gamma(M) with mean 1 (relative spread 1 / sqrt(M)).
inline double speckle_cells(double wavelength_m, double range_m, double spot_diameter_m, double aperture_diameter_m) {
    const double ratio = aperture_diameter_m * spot_diameter_m / (wavelength_m * range_m);
    return 1.0 + ratio * ratio;
}

}  // namespace ladarsim::sensor_model
