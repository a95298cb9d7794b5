#pragma once
// A footprint on one smooth, curved surface, from the rays already traced inside it
// (docs/sensor.md, "Footprint and returns", step 1).
#include <optional>
#include <span>

#include <Eigen/Core>

namespace ladarsim::sensor_model {

/// What one ray inside a footprint met: where it points (footprint offsets), the beam's relative
/// irradiance there, the range, and the echo it saw per unit of the beam's energy up to constants
/// (reflectance cos(incidence) / range^2).
struct SurfaceSample {
    double x_rad, y_rad;
    double irradiance;
    double range_m;
    double seen;
};

/// The surface's echo over the footprint's quadrature: its mean range and spread (weighted by the
/// echo), and the mean echo per unit of the beam (in the samples' units).
struct CurvedPatch {
    double range_m;
    double spread_m;
    double seen;
};

/// The footprint's echo from `samples` of one smooth surface, integrated over `nodes` (equal-energy
/// quadrature nodes of the footprint): the range as a quadratic of the offsets, fitted by least
/// squares weighted by the irradiance (a grazing footprint on terrain spans tens of metres of
/// ground whose curvature leaves any one plane by more than the receiver's resolution), the echo
/// interpolated linearly between neighbouring samples along their lines of equal elevation offset
/// and between those lines (constant beyond the outermost). None when the quadratic is not
/// determined by the samples (fewer than six, or all on one line or conic of offsets), when a
/// sample leaves it by more than `range_tolerance_m` (not one smooth surface), or when a node's
/// range or echo comes out non-positive. `r_max_rad` scales the offsets (the footprint's
/// truncation radius).
std::optional<CurvedPatch> fit_curved_patch(std::span<const SurfaceSample> samples, std::span<const Eigen::Vector2d> nodes,
                                            double r_max_rad, double range_tolerance_m);

}  // namespace ladarsim::sensor_model
