#pragma once
#include <cstdint>
#include <span>
#include <vector>

namespace ladarsim::sensor_model {

/// One sub-ray of a beam: its angular offset from the beam axis and its share of the pulse energy.
struct SubRay {
    double offset_x_rad = 0.0;  ///< along the beam's azimuth direction (left)
    double offset_y_rad = 0.0;  ///< along the beam's elevation direction (up)
    double weight = 0.0;        ///< fraction of the beam's energy; the weights of a beam sum to 1
};

/// The divergence footprint of one beam: a Gaussian irradiance profile
///   I(r) ~ exp(-2 r^2 / w^2),  w = divergence / 2  (the 1/e^2 radius, as an angle),
/// truncated at r_max = truncation * w, holding F = 1 - exp(-2 truncation^2) of the energy
/// (98.9 % at the default 1.5); the weights are renormalised to carry the whole pulse.
///
/// Stratification: the truncated disc is cut into N = `samples` cells of equal energy, a grid
/// in (enclosed energy, angle): round(sqrt(N)) rings of about sqrt(N) sectors each, each ring
/// turned by the golden angle so cells do not line up radially. Since the energy enclosed
/// within radius r is F(r) = 1 - exp(-2 r^2 / w^2), a ring holding cells k0..k1 spans the
/// radii where F(r)/F(r_max) = k0/N .. k1/N: every weight is exactly 1/N.
/// A sub-ray sits at the energy median of its cell (on the axis when N = 1), or, with jitter,
/// at a point drawn from the Gaussian restricted to its cell (an unbiased estimate).
class Footprint {
public:
    Footprint(double divergence_rad, int samples, double truncation);

    int samples() const { return static_cast<int>(cells_.size()); }
    double max_offset_rad() const { return max_radius_rad_; }

    /// Fills `out` (size samples()) with the cell-median sub-rays.
    void fixed(std::span<SubRay> out) const;
    /// Fills `out` with one jittered sub-ray per cell; u[i] are two uniforms in (0, 1] per cell.
    void jittered(std::span<SubRay> out, std::span<const double> uniforms) const;

private:
    struct Cell {
        double energy_lo, energy_hi;  ///< enclosed-energy fraction of the untruncated beam
        double angle_lo_rad, angle_hi_rad;
    };
    SubRay place(const Cell& cell, double u_energy, double u_angle) const;

    double waist_rad_;
    double max_radius_rad_;
    std::vector<Cell> cells_;
};

}  // namespace ladarsim::sensor_model
