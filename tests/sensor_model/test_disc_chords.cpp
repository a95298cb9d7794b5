// A recorded map's discs along one line of a footprint against closed forms: a disc's chord ends,
// the nearer of two overlapping discs hiding the farther, two crossing discs meeting where their
// planes cross.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "ladarsim/sensor_model/footprint/disc_chords.h"

using namespace ladarsim::sensor_model;

namespace {

constexpr double kTMax = 0.05;

Eigen::Vector3d tilted_normal(double tilt_rad) { return {-std::cos(tilt_rad), 0.0, std::sin(tilt_rad)}; }

}  // namespace

TEST_CASE("one disc on one line: its chord ends where the line's plane leaves the disc", "[disc_chords]") {
    const Eigen::Vector3d p(100.0, 0.0, 0.0);
    DiscChord c;
    SECTION("facing the sensor, through its centre") {
        REQUIRE(disc_chord(p, tilted_normal(0.0), 1.0, 0.0, kTMax, c));
        CHECK(c.t_lo == Approx(-0.01).epsilon(1e-12));
        CHECK(c.t_hi == Approx(0.01).epsilon(1e-12));
        // The reciprocal distance to its plane, the same all along (it faces the line).
        CHECK(c.g0 == Approx(0.01).epsilon(1e-12));
        CHECK(c.g1 == Approx(0.0).margin(1e-15));
    }
    SECTION("facing the sensor, half a radius aside: a chord of sqrt(r^2 - d^2)") {
        REQUIRE(disc_chord(p, tilted_normal(0.0), 1.0, 0.005, kTMax, c));
        CHECK(c.t_hi == Approx(std::sqrt(0.75) / 100.0).epsilon(1e-9));
        CHECK(c.t_lo == Approx(-std::sqrt(0.75) / 100.0).epsilon(1e-9));
    }
    SECTION("tilted 60 deg back: its ends at p +- r (sin a, 0, cos a), their ranges along the chord") {
        const double a = 60.0 * M_PI / 180.0;
        REQUIRE(disc_chord(p, tilted_normal(a), 1.0, 0.0, kTMax, c));
        CHECK(c.t_hi == Approx(std::cos(a) / (100.0 + std::sin(a))).epsilon(1e-9));
        CHECK(c.t_lo == Approx(-std::cos(a) / (100.0 - std::sin(a))).epsilon(1e-9));
        // At the upper end the line's direction (1, 0, t) meets the plane at x = 100 + sin a.
        CHECK(1.0 / (c.g0 + c.g1 * c.t_hi) == Approx(100.0 + std::sin(a)).epsilon(1e-9));
    }
    SECTION("clipped to the footprint's extent on the line") {
        REQUIRE(disc_chord(p, tilted_normal(0.0), 1.0, 0.0, 0.004, c));
        CHECK(c.t_lo == -0.004);
        CHECK(c.t_hi == 0.004);
    }
    SECTION("missed by a line beyond its radius, or behind the sensor") {
        CHECK_FALSE(disc_chord(p, tilted_normal(0.0), 1.0, 0.0101, kTMax, c));
        CHECK_FALSE(disc_chord(-p, tilted_normal(0.0), 1.0, 0.0, kTMax, c));
    }
}

TEST_CASE("two overlapping discs on one line: the nearer hides the farther, gaps where neither is", "[disc_chords]") {
    DiscChord near, far;
    REQUIRE(disc_chord({100.0, 0.0, 0.0}, tilted_normal(0.0), 1.0, 0.0, kTMax, near));
    REQUIRE(disc_chord({101.0, 0.0, 1.0}, tilted_normal(0.0), 1.0, 0.0, kTMax, far));
    near.disc = 1;
    far.disc = 2;
    for (const bool near_first : {true, false}) {
        std::vector<DiscChord> chords = near_first ? std::vector<DiscChord>{near, far} : std::vector<DiscChord>{far, near};
        std::vector<VisiblePiece> pieces;
        lower_envelope(chords, -kTMax, kTMax, pieces);
        REQUIRE(pieces.size() == 4);
        CHECK(pieces[0].disc == kGapPiece);
        CHECK(pieces[0].t_hi == Approx(-0.01));
        CHECK(pieces[1].disc == 1);
        CHECK(pieces[1].t_lo == Approx(-0.01));
        CHECK(pieces[1].t_hi == Approx(0.01));
        CHECK(pieces[2].disc == 2);
        CHECK(pieces[2].t_lo == Approx(0.01));
        CHECK(pieces[2].t_hi == Approx(2.0 / 101.0));
        CHECK(pieces[3].disc == kGapPiece);
        CHECK(pieces[3].t_hi == kTMax);
    }
}

TEST_CASE("two crossing discs on one line: each is seen where it is the nearer, up to where their planes cross", "[disc_chords]") {
    // Both centred 100 m out, tilted +-30 deg: their planes cross on the line's axis (t = 0); below
    // it the one tilted back (its lower half leans towards the sensor) is nearer.
    DiscChord back, forward;
    REQUIRE(disc_chord({100.0, 0.0, 0.0}, tilted_normal(M_PI / 6.0), 1.0, 0.0, kTMax, back));
    REQUIRE(disc_chord({100.0, 0.0, 0.0}, tilted_normal(-M_PI / 6.0), 1.0, 0.0, kTMax, forward));
    back.disc = 1;
    forward.disc = 2;
    std::vector<DiscChord> chords{back, forward};
    std::vector<VisiblePiece> pieces;
    lower_envelope(chords, back.t_lo, back.t_hi, pieces);
    REQUIRE(pieces.size() == 2);
    CHECK(pieces[0].disc == 1);
    CHECK(pieces[0].t_hi == Approx(0.0).margin(1e-12));
    CHECK(pieces[1].disc == 2);
    CHECK(pieces[1].t_lo == Approx(0.0).margin(1e-12));
    // Either way nearer than the other along its piece.
    auto distance = [](const DiscChord& c, double t) { return 1.0 / (c.g0 + c.g1 * t); };
    CHECK(distance(back, -0.005) < distance(forward, -0.005));
    CHECK(distance(forward, 0.005) < distance(back, 0.005));
}
