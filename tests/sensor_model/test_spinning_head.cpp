// SpinningHead against the VLP-16's published geometry: 16 channels 2 deg apart, 0.2 deg steps at 10 Hz.
#include <catch2/catch.hpp>

#include <cmath>

#include "ladarsim/sensor_model/sensor/sensor.h"
#include "ladarsim/sensor_model/sensor/spinning_head.h"

using namespace ladarsim::sensor_model;

TEST_CASE("a spinning head fires its channels column by column", "[spinning_head]") {
    const Sensor c = sensor_preset("velodyne_vlp16");
    const ScanPattern& raster = *c.scan;
    REQUIRE(raster.pattern() == "spinning_head");
    REQUIRE(raster.columns() == 1800);
    REQUIRE(raster.rows() == 16);
    // Channels 2 deg apart from +15 to -15 deg; azimuth steps of 0.2 deg over the revolution.
    CHECK(raster.beam(0, 0).el_offset_rad * 180.0 / M_PI == Approx(15.0).epsilon(1e-12));
    CHECK(raster.beam(15, 0).el_offset_rad * 180.0 / M_PI == Approx(-15.0).epsilon(1e-12));
    CHECK((raster.beam(0, 0).az_offset_rad - raster.beam(0, 1).az_offset_rad) * 180.0 / M_PI == Approx(0.2).epsilon(1e-12));
    // 10 Hz: a column every 55.6 us, the 16 channels within it 3.47 us apart.
    CHECK(raster.beam(0, 1).time_offset_s == Approx(0.1 / 1800).epsilon(1e-12));
    CHECK(raster.beam(1, 0).time_offset_s == Approx(0.1 / 1800 / 16).epsilon(1e-12));
    CHECK(raster.beam(15, 1799).time_offset_s < 0.1);
    CHECK(c.pulses_per_beam() == Approx(1.0).epsilon(1e-12));
    CHECK(raster.frame_scan_duration_s() == Approx(0.1).epsilon(1e-12));
}
