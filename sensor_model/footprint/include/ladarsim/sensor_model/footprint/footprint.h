#pragma once
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace ladarsim::sensor_model {

/// atan(t) for the ratios of a footprint's offsets (v.y / v.x of a direction in beam coordinates):
/// below 0.01 the series' first three terms are exact to double precision and cost a fraction of
/// std::atan.
inline double small_atan(double t) {
    if (!(std::abs(t) < 0.01)) return std::atan(t);
    const double t2 = t * t;
    return t * (1.0 - t2 * (1.0 / 3.0 - t2 / 5.0));
}

/// One sub-ray of a beam: its angular offset from the beam axis and its share of the pulse energy.
struct SubRay {
    double offset_x_rad = 0.0;  ///< along the beam's azimuth direction (left)
    double offset_y_rad = 0.0;  ///< along the beam's elevation direction (up)
    double weight = 0.0;        ///< fraction of the beam's energy; the weights of a beam sum to 1
};

/// A box in the footprint's polar energy coordinates: the enclosed-energy fraction of the
/// untruncated beam, F(r) = 1 - exp(-2 r^2 / w^2), in [energy_lo, energy_hi], times the angle in
/// [angle_lo, angle_hi] (angle_hi - angle_lo <= 2 pi; angles may exceed 2 pi). In these coordinates
/// the Gaussian is uniform, so a box's energy is its area.
struct FootprintRegion {
    double energy_lo, energy_hi;
    double angle_lo_rad, angle_hi_rad;
};

/// A rectangle of footprint offsets [x_lo, x_hi] x [y_lo, y_hi] (radians, footprint coordinates).
struct FootprintRect {
    double x_lo, x_hi, y_lo, y_hi;
};

/// The divergence footprint of one beam: a Gaussian irradiance profile
///   I(r) ~ exp(-2 r^2 / w^2),  w = divergence / 2  (the 1/e^2 radius, as an angle),
/// truncated at r_max = truncation * w, holding F = 1 - exp(-2 truncation^2) of the energy
/// (98.9 % at the default 1.5); the weights are renormalised to carry the whole pulse.
///
/// Fixed-count stratification (`fixed`, `jittered`): the truncated disc is cut into N = `samples`
/// cells of equal energy, a grid in (enclosed energy, angle): round(sqrt(N)) rings of about
/// sqrt(N) sectors each, each ring turned by the golden angle so cells do not line up radially.
/// A ring holding cells k0..k1 spans the radii where F(r)/F(r_max) = k0/N .. k1/N: every weight is
/// exactly 1/N. A sub-ray sits at the energy median of its cell (on the axis when N = 1), or, with
/// jitter, at a point drawn from the Gaussian restricted to its cell (an unbiased estimate).
///
/// Adaptive sampling cuts rectangles of offsets (the square around the footprint, or the outline
/// of a small target) into cells of equal energy in (x, y), where the Gaussian is separable
/// (`axis_cdf`, `cell_weight`); a cell whose sub-ray falls beyond the truncation radius carries no
/// energy.
class Footprint {
public:
    Footprint(double divergence_rad, int samples, double truncation);

    int samples() const { return static_cast<int>(cells_.size()); }
    double waist_rad() const { return waist_rad_; }
    double max_offset_rad() const { return max_radius_rad_; }

    /// Fills `out` (size samples()) with the cell-median sub-rays.
    void fixed(std::span<SubRay> out) const;
    /// Fills `out` with one jittered sub-ray per cell; u[i] are two uniforms in (0, 1] per cell.
    void jittered(std::span<SubRay> out, std::span<const double> uniforms) const;
    /// The truncated footprint's variance along an axis over that of its fixed() sub-rays (>= 1,
    /// the same along every axis): a quantity linear across the footprint, such as the range to a
    /// plane, varies this many times as much over the footprint as over those sub-rays, each of
    /// which stands for its cell's mean and misses the cell's own spread.
    double variance_over_fixed() const;

    /// A rectangle clipped to the square around the truncated footprint; empty when outside it.
    std::optional<FootprintRect> clip(const FootprintRect& rect) const;
    /// The square around the truncated footprint.
    FootprintRect square() const;
    bool contains(const FootprintRect& rect, double x_rad, double y_rad) const;
    bool within_truncation(double x_rad, double y_rad) const {
        return x_rad * x_rad + y_rad * y_rad <= max_radius_rad_ * max_radius_rad_;
    }

    /// The separable form of the Gaussian: each axis is a normal distribution of sigma = w / 2, and
    /// cells between equal steps of its CDF, Phi(offset / sigma), carry equal energy. The CDF at an
    /// offset, and the offset at a CDF value.
    double axis_cdf(double offset_rad) const;
    double axis_offset(double cdf) const;
    /// Share of the (truncated, renormalised) beam's energy in a cell spanning `d_cdf_x` x
    /// `d_cdf_y` of the two axis CDFs.
    double cell_weight(double d_cdf_x, double d_cdf_y) const { return d_cdf_x * d_cdf_y / captured_; }

private:
    SubRay place(const FootprintRegion& cell, double u_energy, double u_angle, double weight) const;

    double waist_rad_;
    double max_radius_rad_;
    double captured_;  ///< F(r_max)
    std::vector<FootprintRegion> cells_;
};

}  // namespace ladarsim::sensor_model
