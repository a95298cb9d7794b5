#pragma once
// Steps 2-4 of Algorithm 1: radially bounded nearest-neighbour clustering, outlier removal and the
// rejection of boxes too large to be the target.
#include <vector>

#include "ladarsim/dataset/manifest.h"
#include "ladarsim/detect/point_cloud.h"

namespace ladarsim::detect {

struct Cluster {
    Points points;
    OrientedBox box;  ///< axis-aligned in the sensor frame
};

/// RBNN (Klasing et al. 2008): points closer than `radius_m` are linked; clusters are the
/// connected components (PCL k-d tree radius searches, union-find), largest first.
std::vector<Cluster> rbnn(const Points& points, double radius_m);

/// The V-RBNN radius of Algorithm 1: lambda / (h_scan v_scan) tan(FOV pi / 180) range + bias, range
/// in metres, FOV in degrees. The paper's sensor has a square field (0.5 x 0.5 deg, 150 x 20 beams),
/// so which field angle FOV is does not arise there. Here h_scan = beams_az, v_scan = beams_el and
/// FOV = the smaller of the two field angles: the paper's numbers are unchanged, and a spinning
/// head's 360 deg of azimuth (tan 360 deg = 0; past 90 deg the tangent is meaningless) leaves the
/// radius to its elevation field.
double vrbnn_radius_m(double lambda, const SensorGeometry& sensor, double range_m, double bias_m);

/// The lambda whose V-RBNN radius grows by 1.2 of the sensor's coarser beam pitch per metre of
/// range: returns lie on beam axes, so a target's neighbouring returns are a pitch apart and a
/// smaller radius fragments it (Algorithm 1's lambda = 7 gives 2 cm at 600 m against a 26 cm
/// line pitch). 180 for the paper's raster, about 1,900 for the VLP-16.
double default_lambda(const SensorGeometry& sensor);

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
