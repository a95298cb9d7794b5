// SubRayLattice: the sub-rays a footprint takes from its frame's shared lattice weigh it as the
// beam's truncated Gaussian does.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "ladarsim/sensor_model/render/frame_renderer.h"
#include "ladarsim/sensor_model/footprint/sub_ray_lattice.h"
#include "../support/closed_form_scenario.h"
#include "../support/scene_builders.h"

using namespace ladarsim;
using namespace ladarsim::sensor_model;
using namespace ladarsim::test;

namespace {

struct Bench {
    Scenario scenario;
    std::unique_ptr<raytrace::TracedScene> traced;
    std::unique_ptr<Footprint> footprint;
    double ellipticity = 1.0;
    std::unique_ptr<SubRayLattice> lattice;

    explicit Bench(std::size_t budget) : scenario(closed_form_scenario()) {
        // A 200 m wall 1 km out fills the 8.7 m field; a plate sliding in front of it moves.
        scenario.scene.objects.push_back(object_at(1, plate(200.0, 0.3), fixed_at(1000.0, 0, 0)));
        scenario.scene.objects.push_back(object_at(2, plate(4.0, 0.5), sliding({500.0, -1.0, 0.0}, {0.0, 10.0, 0.0})));
        traced = std::make_unique<raytrace::TracedScene>(scenario.scene, scenario.mount.position_world);
        traced->set_time_window(0.0, 0.25, 2);
        const Transmitter& t = scenario.sensor.transmitter;
        footprint = std::make_unique<Footprint>(t.divergence_mrad * 1e-3, 1, scenario.render.footprint_truncation);
        ellipticity = t.divergence_el_mrad / t.divergence_mrad;
        lattice = std::make_unique<SubRayLattice>(*traced, *scenario.sensor.scan, *footprint, ellipticity, budget,
                                                  scenario.mount.position_world, scenario.mount.world_from_sensor().linear(),
                                                  scenario.sensor.receiver.max_range_m, 7, true,
                                                  [](const raytrace::Hit&) { return 1.0; });
        lattice->start_frame({}, 0);
    }
    /// Where beam (row, step) points, as the renderer aims it with the gimbal at 0.
    Eigen::Matrix3d world_from_beam(int row, int step) const {
        const RasterBeam b = scenario.sensor.scan->beam(row, step);
        return scenario.mount.world_from_sensor().linear() *
               (Eigen::AngleAxisd(b.az_offset_rad, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-b.el_offset_rad, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
    }
    /// A point's footprint offset in a beam, found independently of the lattice: atan2 of the
    /// beam coordinates of the direction to it.
    Eigen::Vector2d offset(const Eigen::Matrix3d& world_from_beam, const Eigen::Vector3d& point_world) const {
        const Eigen::Vector3d v = world_from_beam.transpose() * (point_world - scenario.mount.position_world);
        return {std::atan2(v.y(), v.x()), std::atan2(v.z(), v.x()) / ellipticity};
    }
};

}  // namespace

TEST_CASE("lattice sub-rays weigh a footprint as its truncated Gaussian: share, mean and second moments", "[lattice]") {
    constexpr std::size_t kBudget = 384;
    Bench bench(kBudget);
    const ScanPattern& raster = *bench.scenario.sensor.scan;
    const double w = bench.footprint->waist_rad();
    // Per axis sigma = w / 2; truncated at R = 1.5 w, r^2 / (2 sigma^2) is an exponential truncated
    // at a = 4.5, so E[x^2] = sigma^2 (1 - a e^-a / (1 - e^-a)).
    const double a = std::pow(bench.footprint->max_offset_rad(), 2) / (2.0 * 0.25 * w * w);
    const double second_moment = 0.25 * w * w * (1.0 - a * std::exp(-a) / -std::expm1(-a));
    double mean_x = 0.0, mean_y = 0.0, xx = 0.0, yy = 0.0;
    int beams = 0, moving_seen = 0;
    double worst_share = 0.0, worst_count = 0.0;
    BeamEchoes echoes;
    for (int row = 0; row < raster.rows(); ++row) {
        for (int step = 0; step < raster.columns(); ++step) {
            const Eigen::Matrix3d aim = bench.world_from_beam(row, step);
            echoes.surface.clear();
            bench.lattice->gather(aim, static_cast<std::uint32_t>(row * raster.columns() + step), std::nullopt, 1.0, echoes);
            double share = 0.0;
            for (const SurfaceEcho& e : echoes.surface) {
                moving_seen += e.object_id != 1;  // static geometry only: the sliding plate is not there
                share += e.weight;
                const Eigen::Vector2d o = bench.offset(aim, e.point_world);
                mean_x += e.weight * o.x();
                mean_y += e.weight * o.y();
                xx += e.weight * o.x() * o.x();
                yy += e.weight * o.y() * o.y();
            }
            worst_share = std::max(worst_share, std::abs(share - 1.0));
            worst_count = std::max(worst_count, std::abs(double(echoes.surface.size()) - double(kBudget)) / kBudget);
            ++beams;
        }
    }
    INFO("mean offset " << mean_x / beams / w << ", " << mean_y / beams / w << " w; second moments " << xx / beams / second_moment
                        << ", " << yy / beams / second_moment << " of the closed form");
    CHECK(moving_seen == 0);
    // The wall fills every footprint: its sub-rays carry the whole beam, about the budget of them.
    CHECK(worst_share <= 1e-12);
    CHECK(worst_count <= 0.03);
    CHECK(std::abs(mean_x / beams) <= 0.005 * w);
    CHECK(std::abs(mean_y / beams) <= 0.005 * w);
    CHECK(xx / beams == Approx(second_moment).epsilon(0.01));
    CHECK(yy / beams == Approx(second_moment).epsilon(0.01));
}

TEST_CASE("lattice sub-rays outside an excluded rectangle carry the rest's share", "[lattice]") {
    Bench bench(256);
    const Eigen::Matrix3d aim = bench.world_from_beam(10, 75);
    const double r = bench.footprint->max_offset_rad();
    const FootprintRect left_half{0.0, r, -r, r};  // x is positive to the left
    BeamEchoes echoes;
    bench.lattice->gather(aim, 10 * 150 + 75, left_half, 0.37, echoes);
    REQUIRE(echoes.surface.size() > 100);
    double share = 0.0, rightmost = -1.0;
    for (const SurfaceEcho& e : echoes.surface) {
        share += e.weight;
        rightmost = std::max(rightmost, bench.offset(aim, e.point_world).x());
    }
    CHECK(rightmost < 1e-9);
    CHECK(share == Approx(0.37).epsilon(1e-12));
}

TEST_CASE("lattice tiles are traced once a frame, and a beam's sub-rays do not depend on who traced them", "[lattice]") {
    Bench bench(256);
    const Eigen::Matrix3d aim = bench.world_from_beam(3, 40);
    BeamEchoes first, again;
    bench.lattice->gather(aim, 3 * 150 + 40, std::nullopt, 1.0, first);
    CHECK(first.rays > 0);
    CHECK(first.rays <= static_cast<int>(bench.lattice->size()));
    bench.lattice->gather(aim, 3 * 150 + 40, std::nullopt, 1.0, again);
    CHECK(again.rays == 0);
    REQUIRE(again.surface.size() == first.surface.size());
    bool same = true;
    for (std::size_t i = 0; i < first.surface.size(); ++i)
        same = same && again.surface[i].range_m == first.surface[i].range_m && again.surface[i].weight == first.surface[i].weight;
    CHECK(same);
    // A new frame traces afresh, with other jitter.
    bench.lattice->start_frame({}, 1);
    BeamEchoes next;
    bench.lattice->gather(aim, 3 * 150 + 40, std::nullopt, 1.0, next);
    CHECK(next.rays > 0);
    CHECK(next.surface.front().point_world != first.surface.front().point_world);
}

TEST_CASE("lattice: the overlap of the paper raster's footprints, counted point by point", "[lattice]") {
    // Random points of the field's middle, each tested against every beam's truncated footprint.
    Bench bench(256);
    const ScanPattern& raster = *bench.scenario.sensor.scan;
    std::mt19937 random(5);
    std::uniform_real_distribution<double> az(-0.5 * raster.field_az_rad() + 0.001, 0.5 * raster.field_az_rad() - 0.001);
    std::uniform_real_distribution<double> el(-0.5 * raster.field_el_rad() + 0.001, 0.5 * raster.field_el_rad() - 0.001);
    double holding = 0.0;
    constexpr int kPoints = 200;
    for (int k = 0; k < kPoints; ++k) {
        const double a = az(random), e = el(random);
        const Eigen::Vector3d point = bench.scenario.mount.world_from_sensor().linear() *
                                      Eigen::Vector3d(std::cos(a) * std::cos(e), std::sin(a) * std::cos(e), std::sin(e)) * 1000.0 +
                                      bench.scenario.mount.position_world;
        for (int row = 0; row < raster.rows(); ++row)
            for (int step = 0; step < raster.columns(); ++step) {
                const Eigen::Vector2d o = bench.offset(bench.world_from_beam(row, step), point);
                holding += bench.footprint->within_truncation(o.x(), o.y()) ? 1.0 : 0.0;
            }
    }
    const double overlap = SubRayLattice::overlap(*bench.footprint, bench.ellipticity, raster);
    CHECK(overlap >= SubRayLattice::kMinOverlap);
    CHECK(holding / kPoints == Approx(overlap).epsilon(0.05));
}
