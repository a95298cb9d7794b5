#pragma once
// Steps 2-4 of Algorithm 1: radially bounded nearest-neighbour clustering, outlier removal and the
// rejection of boxes too large to be the target.
#include <vector>

#include "ladarsim/detect/point_cloud.h"

namespace ladarsim::detect {

struct Cluster {
    Points points;
    OrientedBox box;  ///< axis-aligned in the sensor frame
};

/// RBNN (Klasing et al. 2008): points closer than `radius_m` are linked; clusters are the
/// connected components (PCL k-d tree radius searches, union-find), largest first.
std::vector<Cluster> rbnn(const Points& points, double radius_m);

/// The V-RBNN radius of Algorithm 1: lambda / (h_scan * v_scan) * tan(FOV * pi / 180) * range + bias,
/// range in metres, FOV in degrees.
double vrbnn_radius_m(double lambda, int h_scan, int v_scan, double fov_deg, double range_m, double bias_m);

/// Keeps the points with at least `min_neighbours` other points within `radius_m` (PCL's
/// RadiusOutlierRemoval; with Debian's PCL 1.13 the query point itself is not counted).
Points remove_outliers(const Points& points, double radius_m, int min_neighbours);

/// Drops clusters whose box diagonal exceeds `max_diagonal_m` (Algorithm 1: 1 m) plus
/// `beam_spread_rad` times their range, and those with fewer than `min_points`. Returns lie on
/// beam axes, and every beam whose footprint touches a small target reports it: its points spread
/// over a footprint's width (1.5 divergences across the truncated footprint, 1.9 m at 2 km for the
/// paper's sensor) whatever its own size.
std::vector<Cluster> plausible_targets(std::vector<Cluster> clusters, double max_diagonal_m, double beam_spread_rad,
                                       std::size_t min_points);

}  // namespace ladarsim::detect
