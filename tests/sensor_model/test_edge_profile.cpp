// The range profile of one side of a straight edge against an independent integration of the
// truncated Gaussian over that side on a fine grid.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "ladarsim/sensor_model/footprint/edge_profile.h"
#include "../support/footprint_grid.h"

using namespace ladarsim::sensor_model;

namespace {

constexpr double kMaxOffset = 0.465e-3;  // the paper's footprint: 1.5 waists of 0.31 mrad
constexpr double kSigma = 0.155e-3;      // per axis: half the waist
constexpr double kPulseSigma = 0.0637;   // a 1 ns pulse, in range

/// A plane's range over the footprint: metres at the axis, and per radian along x and y.
struct Plane {
    double at_axis, per_x, per_y;
    double at(const Eigen::Vector2d& o) const { return at_axis + per_x * o.x() + per_y * o.y(); }
};

bool on_side(const ChordSide& side, const Eigen::Vector2d& o) { return (side.normal.dot(o) > side.distance) == side.beyond; }

/// The peak of the side's echo, each part a pulse of `kPulseSigma` (stretched by its own spread),
/// found on a 1 mm grid of ranges.
template <typename Parts>
double peak(const Parts& parts) {
    double lo = 1e300, hi = -1e300;
    for (const auto& [range, share, spread] : parts) {
        lo = std::min(lo, range);
        hi = std::max(hi, range);
    }
    double best = 0.0;
    for (double r = lo - 0.3; r <= hi + 0.3; r += 1e-3) {
        double sum = 0.0;
        for (const auto& [range, share, spread] : parts) {
            const double s = std::sqrt(kPulseSigma * kPulseSigma + spread * spread);
            const double z = (r - range) / s;
            if (std::abs(z) < 9.0) sum += share * std::exp(-0.5 * z * z) * kPulseSigma / s;
        }
        best = std::max(best, sum);
    }
    return best;
}

/// The side integrated on a 1001 x 1001 grid over the footprint, binned into 5 mm of range: parts
/// of (range, share, 0).
std::vector<std::array<double, 3>> brute_force(const Plane& plane, const ChordSide& side) {
    constexpr int kGrid = 1001;
    std::vector<std::array<double, 3>> bins;
    double lo = 1e300;
    std::vector<std::pair<double, double>> cells;
    ladarsim::test::for_each_footprint_cell(kGrid, kMaxOffset, [&](double x, double y) {
        const Eigen::Vector2d o(x, y);
        if (!on_side(side, o)) return;
        cells.emplace_back(plane.at(o), std::exp(-0.5 * o.squaredNorm() / (kSigma * kSigma)));
        lo = std::min(lo, cells.back().first);
    });
    double total = 0.0;
    for (const auto& [range, weight] : cells) {
        const auto bin = static_cast<std::size_t>((range - lo) / 0.005);
        if (bin >= bins.size()) bins.resize(bin + 1, {0.0, 0.0, 0.0});
        bins[bin][0] += weight * range;
        bins[bin][1] += weight;
        total += weight;
    }
    std::erase_if(bins, [](const auto& b) { return b[1] == 0.0; });
    for (auto& b : bins) {
        b[0] /= b[1];
        b[1] /= total;
    }
    return bins;
}

std::vector<RangeSample> samples_on(const Plane& plane, const ChordSide& side, int count, double noise_m, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> u(-kMaxOffset, kMaxOffset);
    std::normal_distribution<double> noise(0.0, noise_m);
    std::vector<RangeSample> samples;
    while (static_cast<int>(samples.size()) < count) {
        const Eigen::Vector2d o(u(random), u(random));
        if (o.squaredNorm() > kMaxOffset * kMaxOffset || !on_side(side, o)) continue;
        samples.push_back({o, plane.at(o) + (noise_m > 0.0 ? noise(random) : 0.0)});
    }
    return samples;
}

}  // namespace

TEST_CASE("a side of a straight edge at grazing incidence: its echo's peak as the integrated footprint's", "[edge_profile]") {
    // A crest: the edge across the range's gradient, 5 m of range over the footprint's radius (a
    // plane grazed at 5 deg, 1 km out), the side beyond the edge seen where the beam is brightest;
    // and the edge along the gradient, and tilted, with the side the smaller or the larger part.
    const double tilt_deg = GENERATE(0.0, 30.0, 90.0);
    const double distance = GENERATE(0.0, 0.3, -0.4);  // of the truncation radius
    const bool beyond = GENERATE(true, false);
    INFO("edge turned " << tilt_deg << " deg from across the gradient, " << distance << " r_max from the axis, side beyond: " << beyond);
    const double a = tilt_deg * M_PI / 180.0;
    const ChordSide side{{-std::sin(a), std::cos(a)}, distance * kMaxOffset, beyond};
    const Plane plane{1000.0, 1500.0, 5.0 / kMaxOffset};
    std::vector<RangeSlice> slices;
    const auto fitted = fit_range_plane(samples_on(plane, side, 24, 0.0, 7), kMaxOffset, kPulseSigma);
    REQUIRE(fitted);
    CHECK(fitted->at_axis_m == Approx(plane.at_axis));
    CHECK(fitted->per_rad.x() == Approx(plane.per_x));
    CHECK(fitted->per_rad.y() == Approx(plane.per_y));
    REQUIRE(range_profile(*fitted, side, kMaxOffset, kSigma, kPulseSigma, slices));

    std::vector<std::array<double, 3>> parts;
    double shares = 0.0, mean = 0.0;
    for (const RangeSlice& s : slices) {
        parts.push_back({s.range_m, s.share, s.spread_m});
        shares += s.share;
        mean += s.share * s.range_m;
    }
    const auto want = brute_force(plane, side);
    double want_mean = 0.0;
    for (const auto& b : want) want_mean += b[1] * b[0];
    CHECK(shares == Approx(1.0).epsilon(1e-12));
    CHECK(mean == Approx(want_mean).margin(0.005));
    // The peak of the pulses' sum, relative to the whole side's energy in one pulse.
    const double got_peak = peak(parts), want_peak = peak(want);
    INFO(slices.size() << " slices; peak " << got_peak << " against " << want_peak);
    CHECK(got_peak == Approx(want_peak).epsilon(0.01));
}

TEST_CASE("a side's points that are not on one plane, or on one line, fit no plane", "[edge_profile]") {
    const ChordSide side{{0.0, 1.0}, 0.0, true};
    const Plane plane{1000.0, 0.0, 5.0 / kMaxOffset};
    // Scattered by 1 m about the plane (a tree's leaves): the RMS tolerance asked is 0.5 m.
    CHECK_FALSE(fit_range_plane(samples_on(plane, side, 24, 1.0, 3), kMaxOffset, 0.5));
    // Along one line: a plane through them is not determined.
    std::vector<RangeSample> line;
    for (int k = 0; k < 8; ++k) {
        const Eigen::Vector2d o(0.0, kMaxOffset * k / 8.0);
        line.push_back({o, plane.at(o)});
    }
    CHECK_FALSE(fit_range_plane(line, kMaxOffset, 0.5));
    // The same plane, sampled over the side with 1 cm of noise: a plane.
    CHECK(fit_range_plane(samples_on(plane, side, 24, 0.01, 3), kMaxOffset, 0.5));
}
