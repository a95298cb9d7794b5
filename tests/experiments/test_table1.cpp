// Table 1: the paper's equations against its printed numbers, and rendered counts against bounds
// computed from the raster geometry alone.
#include <catch2/catch.hpp>

#include <cmath>

#include "ladarsim/experiments/table1.h"
#include "ladarsim/scene/trajectory.h"
#include "ladarsim/sensor_model/sensor/galvo_raster.h"
#include "../support/sensors.h"
#include "../support/scene_builders.h"

using namespace ladarsim;
using namespace ladarsim::experiments;
using namespace ladarsim::sensor_model;
using namespace ladarsim::test;

TEST_CASE("Eqs. 4-8 with a 0.65 deg field reproduce Table 1's printed FOV_m, BL and TBI", "[table1]") {
    for (const PrintedTable1Row& row : printed_table1()) {
        INFO("range " << row.range_m);
        const AnalyticPointCount p = paper_point_count(row.range_m, 0.65, 0.3, 150, 20, 0.62);
        CHECK(p.fov_m == Approx(row.fov_m).margin(0.005));
        CHECK(p.lines_az == row.lines_az);
        CHECK(p.lines_el == row.lines_el);
        // To the printed digit; two of the fourteen TBI values are printed truncated rather than
        // rounded (0.35555 as 0.355, 0.45553 as 0.455), hence one unit of the last digit.
        CHECK(p.tbi_az_m == Approx(row.tbi_az_m).margin(0.001));
        CHECK(p.tbi_el_m == Approx(row.tbi_el_m).margin(0.001));
    }
    // The TP column does not follow from Eq. 8: 98 at 200 m (97.49 rounded up) against 105 printed.
    CHECK(paper_point_count(200.0, 0.65, 0.3, 150, 20, 0.62).tp == 98.0);
    // With the stated 0.5 deg field, FOV_m at 2 km is 17.45 m, not 22.69 m.
    CHECK(paper_point_count(2000.0, 0.5, 0.3, 150, 20, 0.62).fov_m == Approx(17.45).margin(0.005));
}

namespace {

/// Beams of the raster whose axis meets a square of side `side` facing the sensor at `range_m` in
/// direction (az, el), and beams whose truncated footprint reaches it: the plate's plane is
/// crossed by each axis at a point whose offset from the centre, in the plate's own axes, decides.
std::pair<int, int> centres_and_touching(const Sensor& c, double range_m, double az, double el, double side) {
    const ScanPattern& raster = *c.scan;
    const Eigen::Quaterniond facing = scene::orientation_from_ypr_deg(180.0 + az * 180.0 / M_PI, -el * 180.0 / M_PI, 0.0);
    const Eigen::Vector3d centre = range_m * Eigen::Vector3d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
    const Eigen::Vector3d n = facing * Eigen::Vector3d::UnitX(), u = facing * Eigen::Vector3d::UnitY(),
                          v = facing * Eigen::Vector3d::UnitZ();
    const double footprint = kTruncation * 0.5 * c.transmitter.divergence_mrad * 1e-3 * range_m;
    int centres = 0, touching = 0;
    for (int row = 0; row < raster.rows(); ++row) {
        for (int k = 0; k < raster.columns(); ++k) {
            const RasterBeam b = raster.beam(row, k);
            const Eigen::Vector3d d(std::cos(b.el_offset_rad) * std::cos(b.az_offset_rad),
                                    std::cos(b.el_offset_rad) * std::sin(b.az_offset_rad), std::sin(b.el_offset_rad));
            const Eigen::Vector3d p = d * (centre.dot(n) / d.dot(n)) - centre;
            const double du = std::max(0.0, std::abs(p.dot(u)) - 0.5 * side), dv = std::max(0.0, std::abs(p.dot(v)) - 0.5 * side);
            centres += du == 0.0 && dv == 0.0;
            touching += std::hypot(du, dv) <= footprint;
        }
    }
    return {centres, touching};
}

}  // namespace

TEST_CASE("rendered plate at 200 m: between the beam centres on it and the footprints touching it", "[table1]") {
    const Sensor c = sensor_preset("paper_ladar");
    const auto plate = test::plate(0.3, 0.5);
    const double pitch_az = c.scan->pitch_az_rad(), pitch_el = c.scan->pitch_el_rad();
    for (double fx : {-0.5, -0.2, 0.0, 0.3}) {
        for (double fy : {-0.4, 0.0, 0.25}) {
            const double az = fx * pitch_az, el = fy * pitch_el;
            const auto [centres, touching] = centres_and_touching(c, 200.0, az, el, 0.3);
            const int rendered = rendered_point_count_at(c, 64, plate, 200.0, az, el, false, 1, 0);
            INFO("offset " << fx << ", " << fy << ": centres " << centres << ", touching " << touching);
            CHECK(rendered >= centres);
            CHECK(rendered <= touching);
        }
    }
}

TEST_CASE("rendered plate counts fall with range", "[table1]") {
    Sensor c = sensor_preset("paper_ladar");
    const auto plate = test::plate(0.3, 0.5);
    double previous = 1e9;
    for (double range : {200.0, 500.0, 800.0, 1400.0, 2000.0}) {
        const CountStatistics s = rendered_point_count(c, 0, plate, range, 12, false, 3);
        INFO("range " << range << ": mean " << s.mean);
        CHECK(s.mean < previous);
        CHECK(s.min <= s.max);
        previous = s.mean;
    }
}
