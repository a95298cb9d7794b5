// EAO on overlap sequences worked by hand.
#include <catch2/catch.hpp>

#include <cmath>

#include "ladarsim/detect/expected_overlap.h"

using namespace ladarsim::detect;

TEST_CASE("fragments: cut at failures, skipped frames dropped, re-initialisations open new ones", "[eao]") {
    //               init  .5   .7   fail skip skip skip skip init .8   .6
    const std::vector<double> iou = {1.0, 0.5, 0.7, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.8, 0.6};
    std::vector<bool> init(iou.size(), false);
    init[0] = init[8] = true;
    const auto f = fragments_of(iou, init);
    REQUIRE(f.size() == 2);
    CHECK(f[0].overlaps == std::vector<double>{1.0, 0.5, 0.7, 0.0});
    CHECK(f[0].ends_in_failure);
    CHECK(f[1].overlaps == std::vector<double>{1.0, 0.8, 0.6});
    CHECK_FALSE(f[1].ends_in_failure);

    // Phi(3) = mean over both fragments of (o2 + o3) / 2: (0.5 + 0.7) / 2 = 0.6 and (0.8 + 0.6) / 2 = 0.7.
    CHECK(expected_overlap(f, 3) == Approx(0.65));
    // Phi(4): the failed fragment counts (0.5 + 0.7 + 0) / 3 = 0.4; the last one is too short.
    CHECK(expected_overlap(f, 4) == Approx(0.4));
    // Phi(6): the failed fragment padded with zeros, (0.5 + 0.7) / 5 = 0.24.
    CHECK(expected_overlap(f, 6) == Approx(0.24));
    // EAO over [3, 4]: (0.65 + 0.4) / 2.
    CHECK(expected_average_overlap(f, 3, 4) == Approx(0.525));
    // EAO is not the mean IoU: an early failure weighs on every longer length.
    CHECK(std::isnan(expected_overlap({}, 5)));
}

TEST_CASE("the VOT length interval holds half the mass about the peak", "[eao]") {
    CHECK(vot_length_interval({40}) == std::pair<int, int>{40, 40});
    CHECK(vot_length_interval({100, 100, 100}) == std::pair<int, int>{100, 100});
    const auto [lo, hi] = vot_length_interval({100, 110, 120, 130, 400});
    CHECK(lo < 115);
    CHECK(hi > 115);
    CHECK(hi < 400);
}
