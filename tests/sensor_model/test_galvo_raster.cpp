// GalvoRaster against the paper's specification: 150 x 20 beams in 0.5 x 0.5 deg, 1 kHz galvo.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "ladarsim/sensor_model/sensor/galvo_raster.h"
#include "../support/sensors.h"
#include "ladarsim/core/units.h"

using namespace ladarsim::sensor_model;
using ladarsim::kDeg;
using ladarsim::test::paper_raster;

namespace {

/// The i-th beam the galvo fires in a frame (lines in order).
RasterBeam fired(const GalvoRaster& r, int i) { return r.beam(i / r.columns(), i % r.columns()); }
}  // namespace

TEST_CASE("paper raster: beam centres sit at cell centres of the 0.5 deg field", "[galvo_raster]") {
    const GalvoRaster raster(paper_raster());
    REQUIRE(raster.columns() == 150);
    REQUIRE(raster.rows() == 20);
    const double pitch_az = 0.5 * kDeg / 150.0;
    const double pitch_el = 0.5 * kDeg / 20.0;

    const RasterBeam first = fired(raster, 0);
    CHECK(first.column == 0);
    CHECK(first.row == 0);
    // Top-left beam: half a pitch inside the field's left and top edges.
    CHECK(first.az_offset_rad == Approx(0.25 * kDeg - 0.5 * pitch_az).epsilon(1e-14));
    CHECK(first.el_offset_rad == Approx(0.25 * kDeg - 0.5 * pitch_el).epsilon(1e-14));

    const RasterBeam last = fired(raster, raster.beam_count() - 1);
    CHECK(last.column == 149);
    CHECK(last.row == 19);
    CHECK(last.az_offset_rad == Approx(-0.25 * kDeg + 0.5 * pitch_az).epsilon(1e-14));
    CHECK(last.el_offset_rad == Approx(-0.25 * kDeg + 0.5 * pitch_el).epsilon(1e-14));

    for (int i = 1; i < 150; ++i) {
        CHECK(fired(raster, i - 1).az_offset_rad - fired(raster, i).az_offset_rad == Approx(pitch_az).epsilon(1e-12));
    }
}

TEST_CASE("paper raster: sawtooth timing, one line per 1 ms galvo period", "[galvo_raster]") {
    const GalvoRaster raster(paper_raster());
    CHECK(fired(raster, 0).time_offset_s == 0.0);
    CHECK(fired(raster, 1).time_offset_s == Approx(1e-3 / 150.0).epsilon(1e-14));
    CHECK(fired(raster, 149).time_offset_s == Approx(149e-3 / 150.0).epsilon(1e-14));
    CHECK(fired(raster, 150).time_offset_s == Approx(1e-3).epsilon(1e-14));
    CHECK(fired(raster, 150).column == 0);
    CHECK(fired(raster, 2999).time_offset_s == Approx(19e-3 + 149e-3 / 150.0).epsilon(1e-14));
    // Emission times strictly increase in firing order.
    for (int i = 1; i < raster.beam_count(); ++i) {
        REQUIRE(fired(raster, i).time_offset_s > fired(raster, i - 1).time_offset_s);
    }
}

TEST_CASE("triangle sweep: two lines per period, odd lines right to left", "[galvo_raster]") {
    GalvoRaster::Parameters p = paper_raster();
    p.sweep = GalvoSweep::triangle;
    const GalvoRaster raster(p);
    CHECK(raster.frame_scan_duration_s() == Approx(10e-3));
    const RasterBeam b = fired(raster, 150);  // first beam of the second line
    CHECK(b.row == 1);
    CHECK(b.column == 149);
    CHECK(b.time_offset_s == Approx(0.5e-3).epsilon(1e-14));
    CHECK(fired(raster, 299).column == 0);
    CHECK(fired(raster, 300).column == 0);
}
