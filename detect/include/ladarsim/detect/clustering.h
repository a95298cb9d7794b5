#pragma once
// Steps 2-4 of Algorithm 1: radially bounded nearest-neighbour clustering, outlier removal and the
// rejection of boxes too large to be the target.
#include <vector>

#include "ladarsim/detect/point_cloud.h"

namespace ladarsim::detect {

struct Cluster {
    Points points;
    sensor_model::OrientedBox box;  ///< axis-aligned in the sensor frame
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

/// Drops clusters whose box diagonal exceeds `max_diagonal_m` (Algorithm 1: 1 m) and those with
/// fewer than `min_points`.
std::vector<Cluster> plausible_targets(std::vector<Cluster> clusters, double max_diagonal_m, std::size_t min_points);

}  // namespace ladarsim::detect
