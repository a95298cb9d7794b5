// Algorithm 1's stages on synthetic point sets whose answers are known by construction.
#include <catch2/catch.hpp>

#include <cmath>
#include <utility>

#include "ladarsim/detect/background_subtraction.h"
#include "ladarsim/detect/clustering.h"
#include "ladarsim/detect/tracker.h"

using namespace ladarsim::detect;
using ladarsim::SensorGeometry;

namespace {

/// The paper's raster: 150 x 20 beams over 0.5 x 0.5 deg, 0.62 mrad beams.
const SensorGeometry kPaperSensor{
    .beams_az = 150, .beams_el = 20, .field_az_deg = 0.5, .field_el_deg = 0.5, .divergence_mrad = 0.62};

/// A grid of points on a plane x = `x`, spacing `step`, `n` x `n`.
Points wall(float x, float step, int n) {
    Points p;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) p.emplace_back(x, step * (i - n / 2), step * (j - n / 2));
    return p;
}

/// A planted target: rows of points like a drone seen by the raster at `range`.
Points drone_at(const Eigen::Vector3f& centre, int columns = 8, int rows = 2, float dy = 0.035f, float dz = 0.26f) {
    Points p;
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < columns; ++c) p.push_back(centre + Eigen::Vector3f(0.0f, dy * (c - columns / 2.0f), dz * (r - rows / 2.0f)));
    return p;
}

}  // namespace

TEST_CASE("background subtraction removes exactly the points near the map", "[detect]") {
    const Points map = wall(2000.0f, 0.5f, 40);
    const BackgroundSubtractor subtract(map, 1.0);
    // The map itself, jittered by 5 cm, disappears entirely.
    Points again = map;
    for (auto& p : again) p += Eigen::Vector3f(0.05f, -0.05f, 0.02f);
    CHECK(subtract.subtract(again).empty());
    // New points far from the map, and outside its bounding box, all survive.
    const Points target = drone_at({600.0f, 3.0f, 2.0f});
    CHECK(subtract.subtract(target).size() == target.size());
    Points mixed = again;
    mixed.insert(mixed.end(), target.begin(), target.end());
    CHECK(subtract.subtract(mixed).size() == target.size());
    // An empty map subtracts nothing; an empty frame gives nothing.
    CHECK(BackgroundSubtractor({}, 1.0).subtract(target).size() == target.size());
    CHECK(subtract.subtract({}).empty());
}

TEST_CASE("background subtraction with a range tolerance removes what lies along the line of sight of the map", "[detect]") {
    // A 20 m wall 2 km ahead (x = 2000, |y|, |z| <= 10) in 1 m voxels dilated by one: points up to
    // about 2 m from it survive a plain subtraction.
    const Points map = wall(2000.0f, 0.5f, 40);
    const Points behind = {{2003.5f, 1.0f, 1.0f}, {1996.6f, -2.0f, 3.0f}};  // 3.4-3.5 m along the line of sight
    const Points beside = {{2000.0f, 13.6f, 0.0f}};                         // 3.6 m off the wall's edge, across
    const Points far = {{2006.0f, 0.0f, 0.0f}};                             // 6 m behind
    const BackgroundSubtractor plain(map, 1.0), tolerant(map, 1.0, 3.0);
    CHECK(plain.subtract(behind).size() == 2);
    CHECK(tolerant.subtract(behind).empty());
    // Only along the line of sight: across it, and beyond the tolerance, points stay.
    CHECK(tolerant.subtract(beside).size() == 1);
    CHECK(tolerant.subtract(far).size() == 1);
    CHECK_THROWS_AS(BackgroundSubtractor(map, 1.0, -1.0), std::invalid_argument);
}

TEST_CASE("RBNN: a radius above the point spacing recovers a planted cluster, one below fragments it", "[detect]") {
    Points cloud = drone_at({600.0f, 0.0f, 20.0f});
    const Points other = drone_at({610.0f, 5.0f, 21.0f}, 4, 1);
    cloud.insert(cloud.end(), other.begin(), other.end());
    const auto linked = rbnn(cloud, 0.3);
    REQUIRE(linked.size() == 2);
    CHECK(linked[0].points.size() == 16);  // largest first
    CHECK(linked[1].points.size() == 4);
    CHECK(linked[0].box.centre.isApprox(Eigen::Vector3d(600.0, -0.0175, 19.87), 1e-4));
    // 0.2 m links the columns (3.5 cm apart) but not the rows (26 cm apart).
    CHECK(rbnn(cloud, 0.2).size() == 3);
    CHECK(rbnn({}, 0.2).empty());
}

TEST_CASE("V-RBNN radius: Algorithm 1's formula, and the lambda that reaches one line pitch", "[detect]") {
    // lambda / (h v) tan(FOV) R + bias with the paper's constants at 600 m: 2.2 cm.
    CHECK(vrbnn_radius_m(7.0, kPaperSensor, 600.0, 0.01) == 7.0 / 3000.0 * std::tan(0.5 * M_PI / 180.0) * 600.0 + 0.01);
    CHECK(vrbnn_radius_m(7.0, kPaperSensor, 600.0, 0.01) == Approx(0.0222).margin(1e-4));
    // lambda = h_scan makes the radius tan(FOV) R / v_scan: one elevation line pitch.
    CHECK(vrbnn_radius_m(150.0, kPaperSensor, 600.0, 0.0) == Approx(std::tan(0.5 * M_PI / 180.0) * 600.0 / 20.0));
}

TEST_CASE("V-RBNN radius: FOV is the smaller field angle, so a spinning head's 360 deg stays finite", "[detect]") {
    // The VLP-16: 1800 x 16 beams over 360 x 32 deg; tan(32 deg) decides, whichever axis it is on.
    const SensorGeometry vlp16{
        .beams_az = 1800, .beams_el = 16, .field_az_deg = 360.0, .field_el_deg = 32.0, .divergence_mrad = 3.0};
    const double expected = 7.0 / (1800.0 * 16.0) * std::tan(32.0 * M_PI / 180.0) * 50.0 + 0.01;
    CHECK(vrbnn_radius_m(7.0, vlp16, 50.0, 0.01) == Approx(expected));
    SensorGeometry turned = vlp16;
    std::swap(turned.field_az_deg, turned.field_el_deg);
    CHECK(vrbnn_radius_m(7.0, turned, 50.0, 0.01) == Approx(expected));
}

TEST_CASE("the default lambda grows the radius by 1.2 of the coarser beam pitch per metre", "[detect]") {
    // The paper's raster: 1.2 x 0.025 deg = 0.524 mrad a metre, which is lambda = 180 (the value
    // the detection tables use).
    CHECK(default_lambda(kPaperSensor) == Approx(180.0).epsilon(1e-3));
    CHECK(vrbnn_radius_m(default_lambda(kPaperSensor), kPaperSensor, 600.0, 0.0) == Approx(1.2 * 0.025 * M_PI / 180.0 * 600.0));
    // The VLP-16's coarser pitch is its 2 deg between channels: 0.42 m at 10 m.
    const SensorGeometry vlp16{1800, 16, 360.0, 32.0, 3.0};
    CHECK(vrbnn_radius_m(default_lambda(vlp16), vlp16, 10.0, 0.0) == Approx(1.2 * 2.0 * M_PI / 180.0 * 10.0));
}

TEST_CASE("outlier removal keeps points with nMin neighbours, and boxes over 1 m are occlusions", "[detect]") {
    // A row of 8 points 3.5 cm apart: with radius 0.06 m each has at most 2 neighbours.
    const Points row = drone_at({600.0f, 0.0f, 0.0f}, 8, 1);
    CHECK(remove_outliers(row, 0.06, 3).empty());
    CHECK(remove_outliers(row, 0.06, 2).size() == 6);  // the two ends have one neighbour each
    CHECK(remove_outliers(row, 0.11, 3).size() == 8);  // within 0.105 m even the ends have three
    // A neighbour exactly at the radius counts (PCL's RadiusOutlierRemoval: the k-th nearest
    // within it), where a strict radius search would drop it.
    const Points pair = {{0.0f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f}};
    CHECK(remove_outliers(pair, 0.5, 1).size() == 2);
    CHECK(remove_outliers(pair, std::nextafter(0.5, 0.0), 1).empty());
    // A 2 m wide cluster is rejected, the drone is kept.
    std::vector<Cluster> clusters = rbnn(wall(300.0f, 0.1f, 21), 0.15);
    const auto drone = rbnn(drone_at({600.0f, 0.0f, 20.0f}), 0.3);
    clusters.insert(clusters.end(), drone.begin(), drone.end());
    const auto kept = plausible_targets(clusters, 1.0, 0.0, 4);
    REQUIRE(kept.size() == 1);
    CHECK(kept[0].points.size() == 16);
    // With the beam's spread allowed (0.93 mrad: 0.28 m more at 300 m) the wall is still too big;
    // 1.5 m square at 2 km is what a 0.3 m target bloomed by 1.9 m footprints looks like.
    CHECK(plausible_targets(rbnn(wall(300.0f, 0.1f, 21), 0.15), 1.0, 0.93e-3, 4).empty());
    CHECK(plausible_targets(rbnn(wall(2000.0f, 0.075f, 21), 0.15), 1.0, 0.93e-3, 4).size() == 1);
}

TEST_CASE("the tracker predicts a straight track through dropped frames (FIR) and resumes", "[detect]") {
    DetectorConfig config;
    config.method = Method::vrbnn;
    config.lambda = 180.0;
    TargetTracker tracker(config, kPaperSensor, {});
    const Eigen::Vector3d velocity(-15.0, 0.5, -0.2);
    const Eigen::Vector3d start(600.0, 30.0, 22.0);
    for (int k = 0; k < 20; ++k) {
        const double t = 0.05 * k;
        const Eigen::Vector3d truth = start + velocity * t;
        // Frames 8-11 lose the target entirely.
        const Points frame = k >= 8 && k < 12 ? Points{} : drone_at(truth.cast<float>(), 8, 2, 0.035f, 0.05f);
        const Detection d = tracker.process(static_cast<std::uint64_t>(k), t, frame);
        REQUIRE(d.found);
        CHECK(d.predicted == (k >= 8 && k < 12));
        // The drone's points are centred on the truth (up to the half column offset of an even row).
        CHECK((d.box.centre - truth).norm() < 0.05);
    }
}

TEST_CASE("an empty cloud is no detection, not a crash", "[detect]") {
    TargetTracker tracker(DetectorConfig{}, kPaperSensor, {});
    const Detection d = tracker.process(0, 0.0, {});
    CHECK_FALSE(d.found);
    CHECK_FALSE(d.predicted);
}
