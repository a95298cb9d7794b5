#include "ladarsim/detect/multi_target.h"

#include <algorithm>
#include <cmath>

#include "ladarsim/detect/box_metrics.h"
#include "ladarsim/detect/clustering.h"
#include "ladarsim/detect/tracking_metrics.h"
#include "ladarsim/core/units.h"

namespace ladarsim::detect {

struct MultiTargetTracker::Track {
    std::uint32_t id = 0;
    double seen_s = 0.0;  ///< when its last cluster was
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
    OrientedBox box, sensor_box;
    std::size_t points = 0;
    int hits = 0;    ///< clusters so far
    int misses = 0;  ///< frames in a row without one
    Eigen::Vector3d predicted(double time_s) const { return centre + velocity * (time_s - seen_s); }
    /// Its cluster of this frame (a new track's first).
    void take(const Cluster& c, double time_s, double spread_rad, const Eigen::Vector3d& target_size_m) {
        if (hits > 0 && time_s > seen_s) velocity = (c.box.centre - centre) / (time_s - seen_s);
        centre = c.box.centre;
        seen_s = time_s;
        box = c.box;
        sensor_box = sensor_aware_box(c.box, spread_rad, target_size_m);
        points = c.points.size();
        ++hits;
        misses = 0;
    }
};

MultiTargetTracker::MultiTargetTracker(const DetectorConfig& config, const SensorGeometry& sensor, const Points& background_map)
    : config_(config), sensor_(sensor), background_(background_map, config.background_resolution_m, config.background_range_tolerance_m) {}

MultiTargetTracker::~MultiTargetTracker() = default;

std::vector<TrackedObject> MultiTargetTracker::process(double time_s, const Points& points) {
    const Points foreground = background_.subtract(points);
    // One clustering radius for the frame, V-RBNN's at the range of the farthest targets.
    const double range = acquisition_range_m(foreground);
    const double radius = config_.method == Method::rbnn
                              ? config_.rbnn_radius_m
                              : vrbnn_radius_m(config_.lambda.value_or(default_lambda(sensor_)), sensor_, range, config_.bias_m);
    const double spread_rad = config_.footprint_divergences * sensor_.divergence_mrad * kMrad;
    std::vector<Cluster> candidates =
        plausible_targets(rbnn(remove_outliers(foreground, radius, config_.min_neighbours), radius), config_.max_object_diagonal_m,
                          spread_rad, static_cast<std::size_t>(config_.min_neighbours) + 1);
    // Clutter: clumps of a cloud's or fog's backscatter, which do not agree in range.
    if (config_.range_coherence_m > 0.0) {
        candidates = range_coherent(std::move(candidates), config_.range_coherence_m, config_.coherent_fraction);
        candidates = standing_clear(std::move(candidates), foreground, radius, 1.0);
    }

    // Tracks against candidates by least total distance, each within the distance its target
    // could have flown since it was last seen (the single-target tracker's gate).
    std::vector<int> candidate_of(tracks_.size(), -1);
    if (!tracks_.empty() && !candidates.empty()) {
        std::vector<std::vector<double>> cost(tracks_.size(), std::vector<double>(candidates.size()));
        std::vector<double> gate(tracks_.size());
        for (std::size_t t = 0; t < tracks_.size(); ++t) {
            gate[t] = config_.max_speed_mps * (time_s - tracks_[t].seen_s) + 0.5;
            const Eigen::Vector3d expected = tracks_[t].predicted(time_s);
            for (std::size_t c = 0; c < candidates.size(); ++c) {
                const double d = (candidates[c].box.centre - expected).norm();
                cost[t][c] = d <= gate[t] ? d : 1e9;
            }
        }
        const std::vector<int> column = least_cost_assignment(cost);
        for (std::size_t t = 0; t < tracks_.size(); ++t)
            if (column[t] >= 0 && cost[t][static_cast<std::size_t>(column[t])] <= gate[t]) candidate_of[t] = column[t];
    }
    std::vector<bool> taken(candidates.size(), false);
    for (std::size_t t = 0; t < tracks_.size(); ++t) {
        Track& track = tracks_[t];
        if (candidate_of[t] < 0) {
            ++track.misses;
            continue;
        }
        taken[static_cast<std::size_t>(candidate_of[t])] = true;
        track.take(candidates[static_cast<std::size_t>(candidate_of[t])], time_s, spread_rad, config_.target_size_m);
    }
    // Unconfirmed tracks end at their first miss, confirmed ones after kMaxMisses.
    std::erase_if(tracks_, [](const Track& t) {
        return t.misses > 0 && (t.hits < kConfirmingHits || t.misses > kMaxMisses);
    });
    for (std::size_t c = 0; c < candidates.size(); ++c) {
        if (taken[c]) continue;
        Track t;
        t.id = next_track_++;
        t.take(candidates[c], time_s, spread_rad, config_.target_size_m);
        tracks_.push_back(t);
    }

    std::vector<TrackedObject> out;
    for (const Track& t : tracks_) {
        if (t.hits < kConfirmingHits) continue;
        TrackedObject o;
        o.track = t.id;
        o.box = t.box;
        o.sensor_box = t.sensor_box;
        o.predicted = t.misses > 0;
        if (o.predicted) {
            o.box.centre = o.sensor_box.centre = t.predicted(time_s);
        } else {
            o.points = t.points;
        }
        o.score = static_cast<double>(t.points) * std::ldexp(1.0, -t.misses);
        out.push_back(o);
    }
    return out;
}

}  // namespace ladarsim::detect
