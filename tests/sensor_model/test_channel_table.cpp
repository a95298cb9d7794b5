// ChannelTable: beams where a calibration table points them, fired column by column.
#include <catch2/catch.hpp>

#include <cmath>

#include "ladarsim/sensor_model/sensor/channel_table.h"
#include "ladarsim/core/units.h"

using namespace ladarsim::sensor_model;
using ladarsim::kDeg;

namespace {

ChannelTable three_channels() {
    ChannelTable::Parameters p;
    p.columns = 1024;
    p.frame_rate_hz = 10.0;
    p.first_column_azimuth_deg = 180.0;
    p.elevation_deg = {12.75, 0.6, -15.32};
    p.azimuth_offset_deg = {4.22, -1.41, -4.24};
    return ChannelTable(p);
}
}  // namespace

TEST_CASE("a channel table points each channel by its own azimuth offset and elevation", "[channel_table]") {
    const ChannelTable t = three_channels();
    REQUIRE(t.columns() == 1024);
    REQUIRE(t.rows() == 3);
    // Column 0: the first column's azimuth plus the channel's offset.
    CHECK(t.beam(0, 0).az_offset_rad == Approx((180.0 + 4.22) * kDeg).epsilon(1e-14));
    CHECK(t.beam(2, 0).az_offset_rad == Approx((180.0 - 4.24) * kDeg).epsilon(1e-14));
    CHECK(t.beam(1, 0).el_offset_rad == Approx(0.6 * kDeg).epsilon(1e-14));
    // Clockwise seen from above: azimuth falls by 360 / 1024 deg a column.
    CHECK(t.beam(1, 0).az_offset_rad - t.beam(1, 1).az_offset_rad == Approx(360.0 / 1024 * kDeg).epsilon(1e-12));
    CHECK(t.beam(1, 512).az_offset_rad == Approx((180.0 - 180.0 - 1.41) * kDeg).margin(1e-14));
    // A column's channels fire together, one column every 1 / (1024 x 10 Hz).
    CHECK(t.beam(0, 7).time_offset_s == t.beam(2, 7).time_offset_s);
    CHECK(t.beam(0, 7).time_offset_s == Approx(7 / 10240.0).epsilon(1e-14));
    CHECK(t.beam_dwell_s() == Approx(1 / 10240.0).epsilon(1e-14));
    CHECK(t.frame_scan_duration_s() == Approx(0.1));
    CHECK(t.beam(1, 5).column == 5);
    CHECK(t.beam(1, 5).row == 1);
}

TEST_CASE("a channel table's elevation pitch is the mean spacing of its channels", "[channel_table]") {
    const ChannelTable t = three_channels();
    CHECK(t.pitch_el_rad() == Approx((12.75 + 15.32) / 2 * kDeg).epsilon(1e-12));
    CHECK(t.pitch_az_rad() == Approx(2 * M_PI / 1024).epsilon(1e-12));
}
