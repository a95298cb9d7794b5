#pragma once
// A footprint on one surface, curved or folded, from the rays already traced inside it
// (docs/sensor.md, "Footprint and returns", step 2).
#include <optional>
#include <span>

#include <Eigen/Core>

namespace ladarsim::sensor_model {

/// What one ray inside a footprint met, in the beam's frame (x along its axis): where it points
/// (footprint offsets, and its unit direction), the beam's relative irradiance there, the range,
/// and the facet it met (unit normal, facing the ray, and reflectance).
struct SurfaceSample {
    double x_rad, y_rad;
    double irradiance;
    double range_m;
    Eigen::Vector3d direction;
    Eigen::Vector3d normal;
    double reflectance;
};

/// A quadrature node of the footprint (an equal-energy cell's centre): offsets and unit direction.
struct PatchNode {
    double x_rad, y_rad;
    Eigen::Vector3d direction;
};

/// The surface's echo over the footprint's nodes: its mean range and spread (weighted by the
/// echo), and the mean echo per unit of the beam, reflectance cos(incidence) / range^2.
struct CurvedPatchFit {
    double range_m;
    double spread_m;
    double seen;
};

/// The footprint's echo from `samples` of one surface, integrated over `nodes`. Each node meets
/// the facet (tangent plane) of a sample: along the samples' lines of equal elevation offset, the
/// nearest's; between two lines, the facet of the line below or above that the surface shows along
/// the node's direction. Where the two facets fold towards the sensor (each one's plane behind the
/// other's point) that is the nearer, where they fold away the farther: the fold between two
/// terrain facets is found where it is. None when the samples are fewer than six or on fewer than
/// three lines, when two facets a node takes from are not a fold but a jump in range (one plane
/// more than `coplanar_m` behind the other's point, the other in front of it: a nearer surface
/// hiding part of a farther one), or when a node's facet is edge-on or behind the sensor.
/// `r_max_rad` scales the offsets (the footprint's truncation radius).
std::optional<CurvedPatchFit> fit_curved_patch(std::span<const SurfaceSample> samples, std::span<const PatchNode> nodes,
                                            double r_max_rad, double coplanar_m);

}  // namespace ladarsim::sensor_model
