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

/// The range V-RBNN's radius is set at when no target is known: the 90th percentile of the
/// points' ranges (those of the farthest targets). A radius below a far target's beam pitch splits
/// it; one above a near target's only joins what lies within it. 0 without points.
double acquisition_range_m(const Points& points);

/// The lambda whose V-RBNN radius grows by 1.2 of the sensor's coarser beam pitch per metre of
/// range: returns lie on beam axes, so a target's neighbouring returns are a pitch apart and a
/// smaller radius fragments it (Algorithm 1's lambda = 7 gives 2 cm at 600 m against a 26 cm
/// line pitch). 180 for the paper's raster, about 1,900 for the VLP-16.
double default_lambda(const SensorGeometry& sensor);

/// Keeps the points with at least `min_neighbours` other points within `radius_m` (PCL's
/// RadiusOutlierRemoval; with Debian's PCL 1.13 the query point itself is not counted).
Points remove_outliers(const Points& points, double radius_m, int min_neighbours);

/// Outlier removal that asks neighbours to agree in range: keeps the points with at least
/// `min_neighbours` other points within `radius_m` whose ranges (from the sensor origin) differ
/// from theirs by at most `tolerance_m`. A surface's neighbouring beams report one range (a small
/// target's to a few centimetres: one footprint mixes its facets); a cloud's or fog's backscatter
/// comes from any depth along each beam, so its returns rarely have such neighbours however dense
/// the volume. A drone inside a cloud keeps its returns, and the volume's around it fall away
/// before clustering could chain them to it.
Points remove_incoherent(const Points& points, double radius_m, double tolerance_m, int min_neighbours);

/// Volume backscatter dropped beam by beam. A return is taken for a cloud's or fog's when its own
/// beam (directions within half `pitch_rad`) holds another return within `window_m` of its range,
/// the echo train of a volume, and no neighbouring beam of the finer scan axis (directions within
/// 1.5 `pitch_rad`: the next beam, not the next but one) holds a return within `tolerance_m` of
/// its range. A surface or a small target is seen by a run of neighbouring beams that all report
/// its range (the bundled drone's to 3 cm from beam to beam), while a volume's returns come from
/// any depth along each beam, independently of the next beam's: in dataset 3's cloud 1 in 5 has
/// such a neighbour, where outlier removal asking 3 neighbours within the clustering radius to
/// agree in range kept 7 in 10 of them over Autzen. A return alone on its beam is never dropped:
/// a far drone's returns miss some beams of its lines (every other one at 1.9 km), and one of
/// them without a neighbouring return would be lost with half its line.
Points without_volume_echoes(const Points& points, double pitch_rad, double tolerance_m, double window_m);

/// A cluster without the scan lines that hold few of its returns: a small target is seen by every
/// beam of a line whose footprint reaches it (about a footprint's width over the azimuth pitch:
/// 16 beams for the paper's raster at any range), while returns of a cloud that happen to agree
/// with it in range and join it from another line come one or two a line, and would move its box
/// by half a line pitch. Lines are told apart by elevation (sensor frame): a gap of more than half
/// `line_pitch_rad` starts a new one. Keeps the lines holding at least `min_fraction` of the
/// fullest line's returns and, given one `intensity` per point, a sparser line whose returns lie
/// within the fullest line's span of azimuth, whose lower median echo is weaker than that line's
/// strongest, and that lies within 1.5 pitches of every line kept for its count: a target's line
/// further from it sees it through the beam's fringe (a few beams above the threshold, under the
/// fullest line's run, as weak as that line's edges but for a glint), as at 1.9 km where the
/// drone lies midway and one line holds 2 returns to the other's 9; a target lower than a pitch
/// that two lines hold lies between them, beyond any third line's fringe. A cloud's return comes
/// from anywhere within the clustering radius, with the cloud's own strength (dataset 3's front
/// layer echoes 4 times the drone's peak; its back layer's weak returns joined the drone at
/// 626 m on the line below the two that held it).
Cluster without_sparse_lines(const Cluster& cluster, double line_pitch_rad, double min_fraction,
                             const std::vector<float>& intensity = {});

/// Whether a cluster's box diagonal is within `max_diagonal_m` plus `beam_spread_rad` times its
/// range (plausible_targets' size test).
bool small_enough(const Cluster& cluster, double max_diagonal_m, double beam_spread_rad);

/// Drops clusters whose box diagonal exceeds `max_diagonal_m` (Algorithm 1: 1 m) plus
/// `beam_spread_rad` times their range, and those with fewer than `min_points`. Returns lie on
/// beam axes, and every beam whose footprint touches a small target reports it: its points spread
/// over a footprint's width (1.5 divergences across the truncated footprint, 1.9 m at 2 km for the
/// paper's sensor) whatever its own size.
std::vector<Cluster> plausible_targets(std::vector<Cluster> clusters, double max_diagonal_m, double beam_spread_rad,
                                       std::size_t min_points);

/// Clutter from clouds and fog. A footprint mixes a small target's facets into one echo, so its
/// returns share a range to a few centimetres whatever their spread across the line of sight; a
/// volume's backscatter comes from every depth along every beam crossing it, and the clumps of it
/// that clustering finds spread in range as much as across. Keeps the clusters with at least
/// `min_fraction` of their returns within `tolerance_m` of their median range (ranges from the
/// sensor origin).
std::vector<Cluster> range_coherent(std::vector<Cluster> clusters, double tolerance_m, double min_fraction);

/// Clutter inside a volume: keeps the clusters that stand clear of the other returns of the frame,
/// with at most `max_ratio` times their own returns among `all` (every return the clustering saw,
/// outliers included) inside their box grown by `margin_m`. A target in clear air has nothing
/// about it; a clump that clustering found inside a cloud's or fog's backscatter is surrounded by
/// more of it, at every depth.
std::vector<Cluster> standing_clear(std::vector<Cluster> clusters, const Points& all, double margin_m, double max_ratio);

/// Each cluster cut down to its coherent core: the most returns whose ranges lie within a window
/// of 2 x `tolerance_m` (a volume's returns that clustering chained to a target fall away), kept
/// where it holds `min_points` or more. A tracker that knows where its target should be takes the
/// core nearest that place: a clump of the volume, or the target freed of it.
std::vector<Cluster> coherent_cores(const std::vector<Cluster>& clusters, double tolerance_m, std::size_t min_points);

/// A cluster cut into the pieces its returns link beam to beam: returns on the same or the next
/// scan line (elevations within 1.5 `el_pitch_rad`) and at most two beams apart along it (azimuths
/// within 2.5 `az_pitch_rad`: a far target's returns miss every other beam) are linked. A small
/// target is seen by a run of neighbouring beams on each line its footprint reaches; a cloud's
/// layer that agrees with it in range, chained to it by a radius of more than a line pitch, lies
/// scattered a few beams apart and falls away from it.
std::vector<Cluster> beam_connected(const Cluster& cluster, double az_pitch_rad, double el_pitch_rad);

}  // namespace ladarsim::detect
