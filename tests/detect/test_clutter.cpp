// Clutter from clouds and fog beside a drone, on closed-form returns: a drone's returns share one
// range across neighbouring beams; a cloud's backscatter climbs in range from beam to beam.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "ladarsim/core/units.h"
#include "ladarsim/detect/clustering.h"
#include "ladarsim/detect/multi_target.h"
#include "ladarsim/detect/tracker.h"
#include "paper_raster.h"

using namespace ladarsim::detect;
using namespace paper_raster;

namespace {

/// A drone's returns: `beams` neighbouring beams on each of 2 lines, every one at `range`, the
/// first beam at (az, el). Rendered, a line has about 16 (a footprint's width over the azimuth pitch).
Points drone(double range, double az, double el, int beams = 8) {
    Points p;
    for (int row = 0; row < 2; ++row)
        for (int column = 0; column < beams; ++column) p.push_back(along(range, az + column * kPitchAz, el + row * kPitchEl));
    return p;
}

/// A cloud's returns along one line: `n` neighbouring beams from (az, el), each `step` m farther
/// than the last, from `range`.
Points backscatter(double range, double az, double el, int n, double step) {
    Points p;
    for (int k = 0; k < n; ++k) p.push_back(along(range + step * k, az + k * kPitchAz, el));
    return p;
}

Points joined(Points a, const Points& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

/// The cued tracker (V-RBNN) over `frames` frames of a drone closing at 25 m/s from 660 m, with
/// `clutter(range)` joined to it in frames [first, last): each frame must detect the drone's own box.
template <typename Clutter>
void check_followed(int frames, int first, int last, const Clutter& clutter) {
    DetectorConfig config;
    config.lambda = 180.0;
    TargetTracker tracker(config, kPaperSensor, {});
    for (int k = 0; k < frames; ++k) {
        const double t = 0.05 * k, range = 660.0 - 25.0 * t;
        const Points target = drone(range, 0.0, 0.0);
        const Points frame = k >= first && k < last ? joined(target, clutter(range)) : target;
        const Detection d = tracker.process(static_cast<std::uint64_t>(k), t, frame);
        INFO("frame " << k);
        REQUIRE(d.found);
        CHECK_FALSE(d.predicted);
        CHECK((d.box.centre - bounding_box(target).centre).norm() < 1e-6);
    }
}

/// A still cloud's clumps beside the drone: four, 1.5-6 m from it, each 8 beams climbing 0.12 m
/// a beam (outlier removal keeps the inner 6, 0.6 m deep).
Points with_cloud_clumps(Points frame) {
    for (int c = 1; c <= 4; ++c) frame = joined(frame, backscatter(650.0 + c, -c * 40 * kPitchAz, c * kPitchEl, 8, 0.12));
    return frame;
}

}  // namespace

TEST_CASE("clutter: a drone's returns agree in range, a cloud's clump climbing 0.12 m a beam does not", "[detect][clutter]") {
    const double radius = vrbnn_radius_m(180.0, kPaperSensor, 650.0, 0.01);
    const std::vector<Cluster> target = rbnn(drone(650.0, 0.0, 0.0), radius);
    const std::vector<Cluster> clump = rbnn(backscatter(650.0, 0.0, 0.0, 8, 0.12), radius);
    REQUIRE(target.size() == 1);
    REQUIRE(clump.size() == 1);  // 0.126 m between neighbours: one cluster, 0.84 m deep
    CHECK(range_coherent(target, 0.1, 0.9).size() == 1);
    CHECK(range_coherent(clump, 0.1, 0.9).empty());
    // Of the clump's 8 returns, only the median one lies within 0.1 m of the median range.
    CHECK(range_coherent(clump, 0.1, 1.0 / 8.0).size() == 1);
    CHECK(range_coherent(clump, 0.1, 2.0 / 8.0).empty());
}

TEST_CASE("clutter: a coherent core frees a drone from the cloud returns chained to it", "[detect][clutter]") {
    // The drone at 650 m; from its last beam a cloud's returns climb 2.9 m behind it, 0.09 m a
    // beam (0.098 m apart: one cluster with the drone, 2.9 m deep).
    const double radius = vrbnn_radius_m(180.0, kPaperSensor, 650.0, 0.01);
    const Points target = drone(650.0, 0.0, 0.0);
    const Points chained = joined(target, backscatter(650.25, 8 * kPitchAz, 0.0, 30, 0.09));
    const std::vector<Cluster> clusters = rbnn(chained, radius);
    REQUIRE(clusters.size() == 1);
    const std::vector<Cluster> cores = coherent_cores(clusters, 0.1, 4);
    REQUIRE(cores.size() == 1);
    CHECK(cores[0].points == target);
    CHECK((cores[0].box.centre - bounding_box(target).centre).norm() < 1e-9);
    // Every 0.2 m window of the chain alone holds 3 of its returns: fewer than 4, no core.
    CHECK(coherent_cores(rbnn(backscatter(650.25, 0.0, 0.0, 30, 0.09), radius), 0.1, 4).empty());
}

TEST_CASE("clutter: the cued tracker keeps a drone flying into a cloud whose returns chain to it", "[detect][clutter]") {
    // Frames 4-7: the cloud's returns climb from the drone's last beam 2.9 m behind it; with them
    // the cluster is too large to be the target, and the drone would be lost.
    check_followed(12, 4, 8, [](double range) { return backscatter(range + 0.25, 8 * kPitchAz, 0.0, 30, 0.09); });
}

TEST_CASE("clutter: tracking every target, a cloud's clumps beside a drone make no track", "[detect][clutter][multi_target]") {
    DetectorConfig config;
    MultiTargetTracker tracker(config, kPaperSensor, {});
    for (int k = 0; k < 10; ++k) {
        const double t = 0.05 * k, range = 660.0 - 25.0 * t;
        const auto tracks = tracker.process(t, with_cloud_clumps(drone(range, 0.0, 0.0)));
        INFO("frame " << k);
        if (k == 0) continue;  // a track is confirmed by its second cluster
        REQUIRE(tracks.size() == 1);
        CHECK((tracks[0].box.centre - bounding_box(drone(range, 0.0, 0.0)).centre).norm() < 1e-6);
    }
    // Without the test the clumps are tracked as targets.
    config.range_coherence_m = 0.0;
    MultiTargetTracker untested(config, kPaperSensor, {});
    std::size_t tracks = 0;
    for (int k = 0; k < 3; ++k) tracks = untested.process(0.05 * k, with_cloud_clumps(drone(660.0 - 1.25 * k, 0.0, 0.0))).size();
    CHECK(tracks == 5);
}

TEST_CASE("clutter: outlier removal that asks neighbours to agree in range drops backscatter, keeps a drone", "[detect][clutter]") {
    const double radius = vrbnn_radius_m(180.0, kPaperSensor, 650.0, 0.01);
    const Points target = drone(650.0, 0.0, 0.0);
    // 8 beams climbing 0.12 m a beam: 2-4 neighbours within the radius, none within 0.1 m in range.
    const Points clump = backscatter(652.0, 20 * kPitchAz, 0.0, 8, 0.12);
    REQUIRE(remove_outliers(clump, radius, 3).size() == 6);
    CHECK(remove_incoherent(clump, radius, 0.1, 3).empty());
    CHECK(remove_incoherent(joined(target, clump), radius, 0.1, 3) == target);
}

TEST_CASE("clutter: a core drops the scan line that a cloud's returns joined it on", "[detect][clutter]") {
    // The drone on two lines of 8 beams; a cloud's return at its range on the line above.
    const Points target = drone(650.0, 0.0, 0.0);
    Points joined_line = target;
    joined_line.push_back(along(650.02, 3 * kPitchAz, 2 * kPitchEl));
    Cluster c{joined_line, bounding_box(joined_line)};
    const Cluster trimmed = without_sparse_lines(c, kPitchEl, 0.25);
    CHECK(trimmed.points == target);
    CHECK((trimmed.box.centre - bounding_box(target).centre).norm() < 1e-9);
    // A line with a quarter of the fullest line's returns stays, and so does a one-line cluster.
    Points quarter = target;
    for (int column = 0; column < 2; ++column) quarter.push_back(along(650.0, column * kPitchAz, 2 * kPitchEl));
    CHECK(without_sparse_lines(Cluster{quarter, bounding_box(quarter)}, kPitchEl, 0.25).points.size() == 18);
    const Points one_line = backscatter(650.0, 0.0, 0.0, 8, 0.0);
    CHECK(without_sparse_lines(Cluster{one_line, bounding_box(one_line)}, kPitchEl, 0.25).points == one_line);
}

TEST_CASE("clutter: the cued tracker follows a drone through a cloud's backscatter on every beam around it", "[detect][clutter]") {
    DetectorConfig config;
    config.lambda = 180.0;
    TargetTracker tracker(config, kPaperSensor, {});
    std::mt19937 random(7);
    std::uniform_real_distribution<double> depth(-3.0, 3.0);
    for (int k = 0; k < 12; ++k) {
        const double t = 0.05 * k, range = 660.0 - 25.0 * t;
        const Points target = drone(range, 0.0, 0.0, 16);
        Points frame = target;
        // Frames 3-9: the drone inside a cloud, a return a beam at any depth within 3 m of it over
        // 40 beams of 7 lines about it: 15 returns a cubic metre, the most dataset 3's cloud has
        // about its drone.
        if (k >= 3 && k < 10)
            for (int row = -3; row <= 3; ++row)
                for (int column = -12; column < 28; ++column) frame.push_back(along(range + depth(random), column * kPitchAz, row * kPitchEl));
        const Detection d = tracker.process(static_cast<std::uint64_t>(k), t, frame);
        INFO("frame " << k);
        REQUIRE(d.found);
        CHECK_FALSE(d.predicted);
        // Within the 0.2 m the paper reports (returns of the cloud that agree with the drone in
        // range on its own lines widen the box along them), and on the drone's lines: a box moved
        // by half a line pitch, 0.14 m, misses a 6 cm drone in height.
        CHECK((d.box.centre - bounding_box(target).centre).norm() < 0.2);
        CHECK(std::abs(d.box.centre.z() - bounding_box(target).centre.z()) < 0.03);
    }
}

TEST_CASE("clutter: a clump inside a cloud's backscatter does not stand clear, a drone in clear air does", "[detect][clutter]") {
    const double radius = vrbnn_radius_m(180.0, kPaperSensor, 640.0, 0.01);
    // A clump of 6 returns agreeing in range (2 lines of 3 beams), and a drone 80 beams away.
    const Points clump = drone(640.0, -40 * kPitchAz, 0.0, 3), target = drone(640.0, 40 * kPitchAz, 0.0, 16);
    std::vector<Cluster> clusters{Cluster{clump, bounding_box(clump)}, Cluster{target, bounding_box(target)}};
    // The cloud about the clump: returns at any depth within the radius of its box, on its beams
    // and the lines above and below (outlier removal dropped them before clustering).
    Points frame = joined(clump, target);
    for (int row = -1; row <= 2; ++row)
        for (int column = -41; column < -36; ++column) frame.push_back(along(640.0 + 0.1 * (column + 39) + 0.05 * row, column * kPitchAz, row * kPitchEl));
    const std::vector<Cluster> clear = standing_clear(clusters, frame, radius, 1.0);
    REQUIRE(clear.size() == 1);
    CHECK(clear[0].points == target);
    // With a return of the cloud fewer than its own, the clump stands clear.
    Points sparse = joined(clump, target);
    for (int column = -41; column < -36; ++column) sparse.push_back(along(640.2, column * kPitchAz, -kPitchEl));
    CHECK(standing_clear(clusters, sparse, radius, 1.0).size() == 2);
}

namespace {

/// A volume's returns about a drone at `range`: two on every beam of lines -3..4 and columns
/// -30..37 (the drone's own beams left out), 2 m apart along the beam, the nearer 0.3 m beyond the
/// drone on even columns and 0.8 m on odd ones. The next but one beam of a line, and every line,
/// agree in range, so each return has many neighbours within the clustering radius that agree
/// with it; the next beam never does.
Points volume_about(double range, int drone_beams) {
    Points p;
    for (int row = -3; row <= 4; ++row)
        for (int column = -30; column <= 37; ++column) {
            if ((row == 0 || row == 1) && column >= 0 && column < drone_beams) continue;
            for (double behind : {0.3, 2.3}) p.push_back(along(range + behind + 0.5 * (column & 1), column * kPitchAz, row * kPitchEl));
        }
    return p;
}

/// `points` with a second return on each beam, `behind_m` farther.
Points with_echo_train(const Points& points, double behind_m) {
    Points out = points;
    for (const auto& p : points) out.push_back(p * static_cast<float>((p.norm() + behind_m) / p.norm()));
    return out;
}

}  // namespace

TEST_CASE("clutter: a return whose beam holds another near it and whose neighbouring beams hold none at its range is dropped", "[detect][clutter]") {
    const Points target = drone(650.0, 0.0, 0.0);
    // Neighbouring beams of a line 0.12 m apart in range, over a tolerance of 0.1 m, each beam
    // with a second return 2 m beyond (a line climbing 0.12 m a beam too): all dropped.
    const Points steep = backscatter(652.0, 20 * kPitchAz, 0.0, 8, 0.12);
    CHECK(without_volume_echoes(with_echo_train(steep, 2.0), kPitchAz, 0.1, 5.0).empty());
    // The second returns 6 m beyond, outside the 5 m window: every return kept, and so are
    // returns alone on their beams.
    CHECK(without_volume_echoes(with_echo_train(steep, 6.0), kPitchAz, 0.1, 5.0).size() == 16);
    CHECK(without_volume_echoes(steep, kPitchAz, 0.1, 5.0) == steep);
    // 0.08 m apart in range: every return has a neighbour at its range, all kept.
    const Points shallow = with_echo_train(backscatter(652.0, 20 * kPitchAz, 0.0, 8, 0.08), 2.0);
    CHECK(without_volume_echoes(shallow, kPitchAz, 0.1, 5.0) == shallow);
    // The drone's returns all share their range with the next beam; the volume's share theirs
    // only with the next but one (2 pitches away) and with other lines (a line pitch, 7.5 azimuth
    // pitches, away), which agreeing-neighbour outlier removal counts.
    const Points frame = joined(target, volume_about(650.0, 8));
    const double radius = vrbnn_radius_m(180.0, kPaperSensor, 650.0, 0.01);
    CHECK(remove_incoherent(frame, radius, 0.1, 3).size() == frame.size());
    CHECK(without_volume_echoes(frame, kPitchAz, 0.1, 5.0) == target);
    // Two beams each with an echo train: a pitch apart at one range, both kept; two pitches apart,
    // neither.
    const Points apart1 = with_echo_train({along(650.0, 0.0, 0.0), along(650.05, kPitchAz, 0.0)}, 2.0);
    CHECK(without_volume_echoes(apart1, kPitchAz, 0.1, 5.0) == apart1);
    CHECK(without_volume_echoes(with_echo_train({along(650.0, 0.0, 0.0), along(650.0, 2 * kPitchAz, 0.0)}, 2.0), kPitchAz, 0.1, 5.0).empty());
}

TEST_CASE("clutter: the cued tracker keeps a drone inside a volume whose returns agree in range from line to line", "[detect][clutter]") {
    // Frames 4-7: the volume about the drone chains to it (0.30 m from its returns, under the
    // clustering radius), and its slab 0.3 m beyond it is the cluster's core: too wide to be the
    // target, and the drone would be lost.
    check_followed(12, 4, 8, [](double range) { return volume_about(range, 8); });
}

TEST_CASE("clutter: a sparse line under the fullest line's run and beside it, typically weaker than its peak, is the target's", "[detect][clutter]") {
    // The drone midway between lines at 1.9 km: 9 returns on one line (echoes 200-1,200), 2 on
    // the other, seen through the beam's fringe, under the first line's run: one of them a glint
    // 4 times the first line's median (dataset 4 over Autzen, frame 59: 2,180 against 543).
    Points target;
    std::vector<float> echoes;
    for (int column = 0; column < 9; ++column) {
        target.push_back(along(1876.3, column * kPitchAz, 0.0));
        echoes.push_back(static_cast<float>(1200.0 - 250.0 * std::abs(column - 4)));
    }
    for (int column : {2, 6}) {
        target.push_back(along(1876.3, column * kPitchAz, kPitchEl));
        echoes.push_back(200.0f);
    }
    echoes[9] = 2200.0f;
    const Cluster c{target, bounding_box(target)};
    CHECK(without_sparse_lines(c, kPitchEl, 0.25, echoes).points == target);
    // Without intensities, or with the sparse line's echoes all brighter than the first line's
    // strongest (a cloud's layer is brighter than a small target), or reaching beyond the run,
    // the line is dropped.
    const Points lower(target.begin(), target.begin() + 9);
    CHECK(without_sparse_lines(c, kPitchEl, 0.25).points == lower);
    std::vector<float> bright = echoes;
    bright[10] = 1300.0f;
    CHECK(without_sparse_lines(c, kPitchEl, 0.25, bright).points == lower);
    Points beyond = target;
    beyond[10] = along(1876.3, 9 * kPitchAz, kPitchEl);
    CHECK(without_sparse_lines(Cluster{beyond, bounding_box(beyond)}, kPitchEl, 0.25, echoes).points == lower);
}

TEST_CASE("clutter: where two lines see the target fully, a weak line beyond either is not its fringe", "[detect][clutter]") {
    // Dataset 3, frame 219: the drone at 626 m between two lines that both hold it (peaks 5.8e4
    // and 5.3e4); the cloud's back layer left 3 weak returns (1.3e3) at its range on the line
    // below the lower one, under their run. The target lies 1.5 pitches from that line: a beam
    // there sees 1e-4 of it.
    Points target;
    std::vector<float> echoes;
    for (int row = 0; row < 2; ++row)
        for (int column = 0; column < 13; ++column) {
            target.push_back(along(626.16, column * kPitchAz, -row * kPitchEl));
            echoes.push_back(static_cast<float>(58000.0 - 7000.0 * std::abs(column - 6)));
        }
    Points with_cloud = target;
    std::vector<float> with_cloud_echoes = echoes;
    for (int column : {8, 10, 11}) {
        with_cloud.push_back(along(625.92, column * kPitchAz, -2 * kPitchEl));
        with_cloud_echoes.push_back(1300.0f);
    }
    CHECK(without_sparse_lines(Cluster{with_cloud, bounding_box(with_cloud)}, kPitchEl, 0.25, with_cloud_echoes).points == target);
    // The same returns beside a target that one line alone holds are its fringe.
    const Points upper(target.begin(), target.begin() + 13);
    const std::vector<float> upper_echoes(echoes.begin(), echoes.begin() + 13);
    Points fringe = upper;
    std::vector<float> fringe_echoes = upper_echoes;
    for (int column : {8, 10, 11}) {
        fringe.push_back(along(626.16, column * kPitchAz, -kPitchEl));
        fringe_echoes.push_back(1300.0f);
    }
    CHECK(without_sparse_lines(Cluster{fringe, bounding_box(fringe)}, kPitchEl, 0.25, fringe_echoes).points == fringe);
}

namespace {

/// A cloud's layer at `range`, one return every 4th beam of lines -3..4, columns -40..-4 and
/// 12..48: the drone's beams (columns 0-7 of lines 0 and 1) 4 or 5 beams from it. Its returns
/// chain along their lines and to the drone within the clustering radius, but no beam's
/// neighbour (within two beams on its line or the next) is one of them.
Points layer_about(double range) {
    Points p;
    for (int row = -3; row <= 4; ++row)
        for (int column = -40; column <= 48; column += 4)
            if (column <= -4 || column >= 12) p.push_back(along(range + 0.03 * (column & 4 ? 1 : -1), column * kPitchAz, row * kPitchEl));
    return p;
}

}  // namespace

TEST_CASE("clutter: a cloud's layer at a drone's range falls away from it beam to beam", "[detect][clutter]") {
    const Points target = drone(650.0, 0.0, 0.0);
    const Points frame = joined(target, layer_about(650.0));
    const double radius = vrbnn_radius_m(180.0, kPaperSensor, 650.0, 0.01);
    const std::vector<Cluster> clusters = coherent_cores(rbnn(frame, radius), 0.1, 4);
    REQUIRE(clusters.size() == 1);  // one core, too wide to be the target
    REQUIRE_FALSE(small_enough(clusters[0], 1.0, 1.5 * 0.62e-3));
    const std::vector<Cluster> pieces = beam_connected(clusters[0], kPitchAz, kPitchEl);
    const auto drone_piece = std::find_if(pieces.begin(), pieces.end(), [&](const Cluster& c) { return c.points.front() == target.front(); });
    REQUIRE(drone_piece != pieces.end());
    CHECK(drone_piece->points == target);
    // A far drone's returns missing every other beam stay one piece.
    Points every_other;
    for (int row = 0; row < 2; ++row)
        for (int column = row; column < 16; column += 2) every_other.push_back(along(1900.0, column * kPitchAz, row * kPitchEl));
    CHECK(beam_connected(Cluster{every_other, bounding_box(every_other)}, kPitchAz, kPitchEl).size() == 1);
}

TEST_CASE("clutter: the cued tracker follows a drone across a cloud's layer at its range", "[detect][clutter]") {
    // Frames 4-6: the layer chains to the drone into one core too wide to be the target.
    check_followed(10, 4, 7, layer_about);
}

TEST_CASE("clutter: before a history, the cued candidate's range sets the clustering radius", "[detect][clutter]") {
    DetectorConfig config;
    config.lambda = 180.0;
    // A drone at 900 m on two lines 0.39 m apart, and a cloud's wall at 650 m holding nine in ten
    // of the returns: the radius at the 90th-percentile range, 0.35 m, splits the drone's lines.
    const Points target = drone(900.0, 0.0, 0.0, 16);
    Points frame = target;
    for (int row = -8; row < -2; ++row)
        for (int column = -60; column < -10; ++column) frame.push_back(along(650.0, column * kPitchAz, row * kPitchEl));
    REQUIRE(vrbnn_radius_m(180.0, kPaperSensor, acquisition_range_m(frame), 0.01) < 900.0 * kPitchEl);
    TargetTracker tracker(config, kPaperSensor, {});
    const Eigen::Vector3d cue = bounding_box(target).centre.normalized();
    const Detection d = tracker.process(0, 0.0, frame, cue);
    REQUIRE(d.found);
    CHECK(d.points == target.size());
    CHECK((d.box.centre - bounding_box(target).centre).norm() < 1e-6);
}
