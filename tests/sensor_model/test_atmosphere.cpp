// Kim/Kruse extinction at 1560 nm against the formula worked by hand and physics.md's values.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "ladarsim/sensor_model/signal/atmosphere.h"

using ladarsim::sensor_model::kim_extinction_per_m;

TEST_CASE("extinction at 1560 nm for 23, 5 and 1 km visibility", "[atmosphere]") {
    // alpha = 3.912 / V * (1560 / 550)^-q, by hand:
    //   V = 23 km: q = 1.3:               0.170087 / km * 0.257875 = 0.043861 / km
    //   V =  5 km: q = 0.16 * 5 + 0.34:   0.7824   / km * 0.304685 = 0.238386 / km
    //   V =  1 km: q = 1 - 0.5 = 0.5:     3.912    / km * 0.593771 = 2.322832 / km
    CHECK(kim_extinction_per_m(23e3, 1560.0) * 1e3 == Approx(0.043861).epsilon(1e-4));
    CHECK(kim_extinction_per_m(5e3, 1560.0) * 1e3 == Approx(0.238386).epsilon(1e-4));
    CHECK(kim_extinction_per_m(1e3, 1560.0) * 1e3 == Approx(2.322832).epsilon(1e-4));
    // physics.md quotes 0.044, 0.24 and 2.3 per km.
    CHECK(kim_extinction_per_m(23e3, 1560.0) * 1e3 == Approx(0.044).margin(0.0005));
    CHECK(kim_extinction_per_m(5e3, 1560.0) * 1e3 == Approx(0.24).margin(0.005));
    CHECK(kim_extinction_per_m(1e3, 1560.0) * 1e3 == Approx(2.3).margin(0.05));
}

TEST_CASE("Kim's q: every branch, no wavelength dependence in thick fog, none at all in a vacuum", "[atmosphere]") {
    CHECK(kim_extinction_per_m(80e3, 1560.0) == Approx(3.912 / 80e3 * std::pow(1560.0 / 550.0, -1.6)));
    CHECK(kim_extinction_per_m(700.0, 1560.0) == Approx(3.912 / 700.0 * std::pow(1560.0 / 550.0, -0.2)));
    CHECK(kim_extinction_per_m(300.0, 1560.0) == Approx(3.912 / 300.0));
    CHECK(kim_extinction_per_m(300.0, 905.0) == kim_extinction_per_m(300.0, 1560.0));
    CHECK(kim_extinction_per_m(std::numeric_limits<double>::infinity(), 1560.0) == 0.0);
    // At 550 nm the visibility definition itself: 2 % contrast over V, ln(50) = 3.912.
    CHECK(std::exp(-kim_extinction_per_m(10e3, 550.0) * 10e3) == Approx(0.02).epsilon(1e-3));
}
