#include <catch2/catch.hpp>

#include "ladarsim/detect/box_metrics.h"

using ladarsim::detect::axis_aligned_iou;
using ladarsim::detect::centre_distance_m;
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
