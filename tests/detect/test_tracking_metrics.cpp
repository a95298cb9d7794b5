// CLEAR MOT and nuScenes-style centre-distance AP against sequences worked out by hand.
#include <catch2/catch.hpp>

#include <cmath>

#include "ladarsim/detect/tracking_metrics.h"

using namespace ladarsim::detect;

namespace {

TruthCentre object(std::uint32_t id, double x, const char* cls = "drone") { return {id, cls, Eigen::Vector3d(x, 0, 0)}; }
TrackCentre track(std::uint32_t id, double x, double score = 1.0) { return {id, Eigen::Vector3d(x, 0, 0), score}; }

}  // namespace

TEST_CASE("least-cost assignment: the cheapest pairing, not the greedy one", "[tracking_metrics]") {
    // Greedy would take the 1 and then pay 100; the best pairing costs 2 + 3.
    const std::vector<int> a = least_cost_assignment({{1, 2}, {3, 100}});
    CHECK(a == std::vector<int>{1, 0});
    // More rows than columns: one row stays unassigned.
    const std::vector<int> b = least_cost_assignment({{5}, {1}, {9}});
    CHECK(b == std::vector<int>{-1, 0, -1});
}

TEST_CASE("CLEAR MOT on a hand-made sequence: a miss, a false positive, an ID switch, kept correspondences",
          "[tracking_metrics]") {
    // Objects A (id 1) and B (id 2, a bird) move along x; tracks 1, 2, then 3 takes B over.
    std::vector<std::vector<TruthCentre>> truth = {
        {object(1, 0), object(2, 10, "bird")},
        {object(1, 1), object(2, 11, "bird")},
        {object(1, 2), object(2, 12, "bird")},
        {object(1, 3), object(2, 13, "bird")},
        {object(1, 4), object(2, 4.5, "bird")},
    };
    std::vector<std::vector<TrackCentre>> tracks = {
        {track(1, 0.1), track(2, 10.2)},               // A-1 0.1, B-2 0.2
        {track(1, 1.1), track(2, 11.0)},               // A-1 0.1, B-2 0
        {track(1, 2.0)},                               // A-1 0; B missed
        {track(1, 3.0), track(3, 13.1), track(4, 50)}, // A-1 0; B-3 0.1, a switch from 2; 4 false
        // Least total distance would swap them (A-3 and B-1 at 0), but last frame's pairs A-1
        // and B-3 are still within the 2 m gate: kept, no switch.
        {track(1, 4.5), track(3, 4.0)},                // A-1 0.5, B-3 0.5
    };
    const ClearMot m = clear_mot(truth, tracks, 2.0);
    // 10 objects; 1 miss + 1 false positive + 1 switch: MOTA = 1 - 3 / 10.
    CHECK(m.all.objects == 10);
    CHECK(m.all.misses == 1);
    CHECK(m.false_positives == 1);
    CHECK(m.all.id_switches == 1);
    CHECK(m.mota() == Approx(0.7));
    // 9 matches, distances 0.1 + 0.2 + 0.1 + 0 + 0 + 0 + 0.1 + 0.5 + 0.5 = 1.5 m.
    CHECK(m.all.matches == 9);
    CHECK(m.motp_m() == Approx(1.5 / 9));
    // The miss and the switch were the bird's.
    CHECK(m.per_class.at("bird").misses == 1);
    CHECK(m.per_class.at("bird").id_switches == 1);
    CHECK(m.per_class.at("drone").matches == 5);
    CHECK(m.per_class.at("drone").id_switches == 0);
}

TEST_CASE("centre-distance AP as nuScenes computes it, on a ranked list worked by hand", "[tracking_metrics]") {
    // Two objects; hypotheses by score: 0.9 hits A, 0.8 hits nothing, 0.7 hits B.
    // Cumulative: precision 1, 1/2, 2/3 at recall 1/2, 1/2, 1. Interpolated at recall k / 100:
    // 1 below 0.5; at 0.5 the last of the equal recalls, 1/2; then linear from 1/2 to 2/3.
    // Kept k = 11..100 (90 values), less 0.1: 39 x 0.9 + 0.4 + sum_{m=1..50} (0.4 + m / 300)
    // = 35.1 + 0.4 + 20 + 1275 / 300 = 59.75; AP = 59.75 / 90 / 0.9.
    const std::vector<std::vector<TruthCentre>> truth = {{object(1, 0), object(2, 10)}};
    const std::vector<std::vector<TrackCentre>> tracks = {{track(7, 0.1, 0.9), track(8, 30, 0.8), track(9, 10.3, 0.7)}};
    CHECK(centre_distance_ap(truth, tracks, 0.5) == Approx(59.75 / 90.0 / 0.9));
    // With a 0.25 m gate the 0.7 hypothesis (0.3 m off) is a false positive too: precision 1, 1/2, 1/3
    // at recall 1/2: 1 up to k = 49, 1/3 at 50 (the last equal recall), 0 beyond.
    // (39 x 0.9 + (1/3 - 0.1)) / 90 / 0.9.
    CHECK(centre_distance_ap(truth, tracks, 0.25) == Approx((39 * 0.9 + (1.0 / 3.0 - 0.1)) / 90.0 / 0.9));
    // No hypothesis at all: AP 0; no ground truth: undefined.
    CHECK(centre_distance_ap(truth, {{}}, 1.0) == 0.0);
    CHECK(std::isnan(centre_distance_ap({{}}, tracks, 1.0)));
    // The mean over 0.25, 0.5, 1 and 2 m (1 and 2 m as 0.5 m here).
    const CentreDistanceAp aps = centre_distance_aps(truth, tracks);
    CHECK(aps.at[0] == centre_distance_ap(truth, tracks, 0.25));
    CHECK(aps.mean == Approx((centre_distance_ap(truth, tracks, 0.25) + 3 * centre_distance_ap(truth, tracks, 0.5)) / 4));
}

TEST_CASE("centre-distance AP measures on the ground plane as nuScenes does, and in 3-D on request", "[tracking_metrics]") {
    // The ranked list above with the 0.7 hypothesis 0.3 m beside B and 1.5 m above it: on the
    // ground plane 0.3 m off (a hit within 0.5 m, as above), in 3-D sqrt(0.09 + 2.25) = 1.53 m
    // (a false positive within 0.5 m: precision 1, 1/2, 1/3 as at 0.25 m above; a hit within 2 m).
    const std::vector<std::vector<TruthCentre>> truth = {{object(1, 0), object(2, 10)}};
    const std::vector<std::vector<TrackCentre>> tracks = {
        {track(7, 0.1, 0.9), track(8, 30, 0.8), {9, Eigen::Vector3d(10, 0.3, 1.5), 0.7}}};
    const double hit = 59.75 / 90.0 / 0.9, missed = (39 * 0.9 + (1.0 / 3.0 - 0.1)) / 90.0 / 0.9;
    CHECK(centre_distance_ap(truth, tracks, 0.5) == Approx(hit));  // nuScenes' is the default
    CHECK(centre_distance_ap(truth, tracks, 0.5, CentreDistance::ground_plane) == Approx(hit));
    CHECK(centre_distance_ap(truth, tracks, 0.5, CentreDistance::three_d) == Approx(missed));
    CHECK(centre_distance_ap(truth, tracks, 2.0, CentreDistance::three_d) == Approx(hit));
    CHECK(centre_distance_aps(truth, tracks, CentreDistance::three_d).at[1] == Approx(missed));
}
