#pragma once
// Multi-object tracking scores by box centres: CLEAR MOT (Bernardin and Stiefelhagen 2008) and a
// centre-distance average precision as nuScenes computes it (Caesar et al. 2020, calc_ap).
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace ladarsim::detect {

/// A ground-truth object in one frame.
struct TruthCentre {
    std::uint32_t id = 0;
    std::string object_class;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};

/// A tracker's hypothesis in one frame: its track id, where, and how sure (ranks it for AP).
struct TrackCentre {
    std::uint32_t track = 0;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double score = 0.0;
};

/// What CLEAR MOT counts over a sequence, and per class of the ground truth (false positives
/// belong to no class: a class-agnostic tracker does not say what it follows).
struct ClearMotCounts {
    int objects = 0;      ///< ground-truth objects summed over frames
    int matches = 0;
    int misses = 0;
    int id_switches = 0;
    double distance_sum_m = 0.0;  ///< over matches
};
struct ClearMot {
    ClearMotCounts all;
    int false_positives = 0;
    std::map<std::string, ClearMotCounts> per_class;
    double mota() const;    ///< 1 - (misses + false positives + ID switches) / objects
    double motp_m() const;  ///< mean centre distance of the matches
};

/// CLEAR MOT with centre distance and `threshold_m` as the match gate. Each frame keeps last
/// frame's correspondences that are still within the gate, then matches the rest by least total
/// distance (Hungarian); an object matched to another track than the one it last had is an ID
/// switch. `truth` and `tracks` hold one list per frame, the same number of frames.
ClearMot clear_mot(const std::vector<std::vector<TruthCentre>>& truth, const std::vector<std::vector<TrackCentre>>& tracks,
                   double threshold_m);

/// How far a hypothesis' centre is from an object's: on the ground plane, as nuScenes measures it
/// (`center_distance`: x and y of centres given in a frame whose z is up), or in 3-D.
enum class CentreDistance { ground_plane, three_d };

/// nuScenes' average precision at one centre-distance threshold: hypotheses of the whole
/// sequence ranked by score, each matched to the nearest unmatched object of its frame when
/// nearer than `threshold_m` by `distance` (else a false positive); precision against recall sampled at 101
/// recalls by linear interpolation (0 beyond the highest recall), those above `min_recall`
/// (0.1) kept, less `min_precision` (0.1) and clipped at 0, averaged and divided by
/// 1 - min_precision. NaN without ground truth.
double centre_distance_ap(const std::vector<std::vector<TruthCentre>>& truth, const std::vector<std::vector<TrackCentre>>& tracks,
                          double threshold_m, CentreDistance distance = CentreDistance::ground_plane, double min_recall = 0.1,
                          double min_precision = 0.1);

/// centre_distance_ap at 0.25, 0.5, 1 and 2 m (nuScenes takes 0.5-4 m for cars; a drone is
/// 0.3 m across), and their mean.
struct CentreDistanceAp {
    static constexpr std::array<double, 4> kThresholds_m{0.25, 0.5, 1.0, 2.0};
    std::array<double, 4> at{};  ///< at each of kThresholds_m
    double mean = 0.0;
};
CentreDistanceAp centre_distance_aps(const std::vector<std::vector<TruthCentre>>& truth,
                                     const std::vector<std::vector<TrackCentre>>& tracks,
                                     CentreDistance distance = CentreDistance::ground_plane);

/// Least-total-cost assignment of rows to columns (Hungarian, O(n^3)) of a rows x columns matrix;
/// returns for each row its column, or -1 (more rows than columns).
std::vector<int> least_cost_assignment(const std::vector<std::vector<double>>& cost);

}  // namespace ladarsim::detect
