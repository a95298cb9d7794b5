#pragma once
// The monostatic Lambertian range equation, per sub-ray. Summed over a beam's sub-rays it gives
// the extended-target law (1/R^2, target filling the footprint) and the point-target law (1/R^4,
// target smaller than the footprint, through the fraction of sub-rays that hit it) without a
// switch between them.
#include <cmath>
#include <numbers>

namespace ladarsim::sensor_model {

/// `energy` times the view factor from a small Lambertian patch at `range_m` to the coaxial
/// receiver aperture of squared radius `aperture_radius2_m2`, r_a^2 / (R^2 + r_a^2): the familiar
/// A_r / (pi R^2) once R >> r_a, and below 1 as R -> 0, so no echo carries more than it was sent.
/// Every received-power formula (surfaces, volumes, plane patches) goes through it.
inline double through_aperture(double energy, double aperture_radius2_m2, double range_m) {
    return energy * aperture_radius2_m2 / (range_m * range_m + aperture_radius2_m2);
}

/// r_a^2 of a round aperture of area `aperture_area_m2`.
inline double aperture_radius2_m2(double aperture_area_m2) { return aperture_area_m2 / std::numbers::pi; }

/// Energy reaching the detector from one sub-ray (J):
///   E = E_pulse * w * eta * T^2 * rho * cos(theta) * r_a^2 / (R^2 + r_a^2),
/// w the sub-ray's share of the pulse energy, eta the optics efficiency, T the one-way
/// transmission, rho the diffuse reflectance, theta the incidence angle, r_a the aperture radius
/// (the last factor: through_aperture).
inline double lambertian_echo_energy_j(double pulse_energy_j, double weight, double optics_efficiency,
                                       double two_way_transmission, double reflectance, double cos_incidence,
                                       double aperture_area_m2, double range_m) {
    return through_aperture(pulse_energy_j * weight * optics_efficiency * two_way_transmission * reflectance * cos_incidence,
                            aperture_radius2_m2(aperture_area_m2), range_m);
}

/// Number of speckle cells averaged by the aperture, M = 1 + (D_r * D_spot / (lambda R))^2: the
/// aperture area over the area of one speckle (lambda R / D_spot across). The received energy of a
/// rough target fluctuates as Gamma(M) with mean 1 (relative spread 1 / sqrt(M)).
inline double speckle_cells(double wavelength_m, double range_m, double spot_diameter_m, double aperture_diameter_m) {
    const double ratio = aperture_diameter_m * spot_diameter_m / (wavelength_m * range_m);
    return 1.0 + ratio * ratio;
}

}  // namespace ladarsim::sensor_model
