#include <catch2/catch.hpp>

#include "ladarsim/detect/box_metrics.h"

using ladarsim::detect::axis_aligned_iou;
using ladarsim::detect::bev_iou;
using ladarsim::detect::centre_distance_m;
using ladarsim::detect::sensor_aware_box;
using ladarsim::OrientedBox;

namespace {
OrientedBox box(double x, double y, double z, double sx, double sy, double sz) {
    OrientedBox b;
    b.centre = {x, y, z};
    b.size = {sx, sy, sz};
    return b;
}
}  // namespace

TEST_CASE("centre distance is the Euclidean norm of the centre offset", "[box_metrics]") {
    CHECK(centre_distance_m(box(0, 0, 0, 1, 1, 1), box(3, 4, 0, 1, 1, 1)) == Approx(5.0));
}

TEST_CASE("IoU of boxes against hand-computed overlaps", "[box_metrics]") {
    // Identical boxes overlap completely.
    CHECK(axis_aligned_iou(box(1, 2, 3, 1, 2, 3), box(1, 2, 3, 1, 2, 3)) == Approx(1.0));
    // Unit cubes shifted by half a side: intersection 0.5, union 1.5.
    CHECK(axis_aligned_iou(box(0, 0, 0, 1, 1, 1), box(0.5, 0, 0, 1, 1, 1)) == Approx(1.0 / 3.0));
    // A 1 m cube inside a 2 m cube: 1 / 8.
    CHECK(axis_aligned_iou(box(0, 0, 0, 1, 1, 1), box(0, 0, 0, 2, 2, 2)) == Approx(0.125));
    // Disjoint and degenerate boxes give zero.
    CHECK(axis_aligned_iou(box(0, 0, 0, 1, 1, 1), box(5, 0, 0, 1, 1, 1)) == 0.0);
    CHECK(axis_aligned_iou(box(0, 0, 0, 0, 1, 1), box(0, 0, 0, 0, 1, 1)) == 0.0);
}

TEST_CASE("bird's-eye IoU: the boxes' x-y footprints, heights ignored", "[box_metrics]") {
    // Unit squares shifted by half a side along y: intersection 0.5, union 1.5, whatever z does.
    CHECK(bev_iou(box(0, 0, 0, 1, 1, 1), box(0, 0.5, 7, 1, 1, 0.1)) == Approx(1.0 / 3.0));
    // A 1 x 2 footprint inside a 2 x 2: 2 / 4.
    CHECK(bev_iou(box(0, 0, 0, 1, 2, 5), box(0, 0, 0, 2, 2, 1)) == Approx(0.5));
    // Side by side, and a footprint of no area.
    CHECK(bev_iou(box(0, 0, 0, 1, 1, 1), box(1.5, 0, 0, 1, 1, 1)) == 0.0);
    CHECK(bev_iou(box(0, 0, 0, 0, 1, 1), box(0, 0, 0, 1, 1, 1)) == 0.0);
    // Where 3-D IoU sees boxes at different heights as disjoint, bird's-eye view sees them agree.
    CHECK(axis_aligned_iou(box(0, 0, 0, 1, 1, 0.1), box(0, 0, 0.2, 1, 1, 0.1)) == 0.0);
    CHECK(bev_iou(box(0, 0, 0, 1, 1, 0.1), box(0, 0, 0.2, 1, 1, 0.1)) == Approx(1.0));
}

TEST_CASE("the sensor-aware box takes a footprint's spread off the returns' box, across the line of sight", "[box_metrics]") {
    const Eigen::Vector3d prior(0.3, 0.3, 0.06);
    const double width_rad = 0.93e-3;  // 1.5 x 0.62 mrad: 0.93 m at 1 km
    SECTION("a drone 1 km ahead: its returns cannot give its size, only its place") {
        // Returns of a 0.3 x 0.3 x 0.06 m drone drawn a footprint wider across the line of sight
        // (y and z), 5 cm deep in range.
        const OrientedBox b = sensor_aware_box(box(1000, 2, 3, 0.05, 0.3 + 0.93, 0.06 + 0.93), width_rad, prior);
        CHECK(b.centre == Eigen::Vector3d(1000, 2, 3));
        CHECK(b.size.x() == Approx(0.3));   // 0.05: the prior
        CHECK(b.size.y() == Approx(0.3).margin(1e-4));  // 1.23 less the spread (0.93 m x 0.999998)
        CHECK(b.size.z() == Approx(0.06).margin(1e-4));
    }
    SECTION("a 10 x 3 m aircraft at 1 km: its extent is resolved, and the spread comes off it") {
        const OrientedBox b = sensor_aware_box(box(1000, 0, 0, 0.5, 10.0 + 0.93, 3.0 + 0.93), width_rad, prior);
        CHECK(b.size.x() == Approx(0.5));  // along the line of sight nothing is spread
        CHECK(b.size.y() == Approx(10.0));
        CHECK(b.size.z() == Approx(3.0));
    }
    SECTION("an oblique line of sight spreads each axis by the disc's projection on it") {
        // Line of sight (0.6, 0.8, 0) at 1 km: the footprint's disc spans 0.8 w along x, 0.6 w
        // along y, w along z.
        const OrientedBox b = sensor_aware_box(box(600, 800, 0, 20, 20, 20), width_rad, prior);
        CHECK(b.size.x() == Approx(20 - 0.8 * 0.93));
        CHECK(b.size.y() == Approx(20 - 0.6 * 0.93));
        CHECK(b.size.z() == Approx(20 - 0.93));
    }
}
