// render_dataset's manifest, as readers of a dataset take it: the sensor's geometry (divergence
// the wider axis) and the gimbal's pointing for every frame.
#include <catch2/catch.hpp>

#include <algorithm>

#include "ladarsim/dataset/manifest.h"
#include "ladarsim/sensor_model/render_dataset.h"
#include "../support/closed_form_scenario.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;
using namespace ladarsim::sensor_model;

TEST_CASE("a rendered dataset's manifest says which sensor took it, as read_manifest reads it", "[render_dataset]") {
    const test::ScratchDir dir;
    Scenario s = test::closed_form_scenario();
    s.file = dir / "scenario.json";  // the manifest records where the scenario came from
    SECTION("the paper's LADAR, its beam wider in elevation") { s.sensor.transmitter.divergence_el_mrad = 0.9; }
    SECTION("the VLP-16") { s.sensor = sensor_preset("velodyne_vlp16"); }
    DatasetOptions options;
    options.out_dir = dir / "d";
    options.frames = 2;
    render_dataset(s, options);
    const Manifest m = read_manifest(dir / "d" / "manifest.json");
    const ScanPattern& scan = *s.sensor.scan;
    CHECK(m.sensor.beams_az == scan.columns());
    CHECK(m.sensor.beams_el == scan.rows());
    CHECK(m.sensor.field_az_deg == Approx(scan.field_az_deg()).epsilon(1e-15));
    CHECK(m.sensor.field_el_deg == Approx(scan.field_el_deg()).epsilon(1e-15));
    CHECK(m.sensor.divergence_mrad == std::max(s.sensor.transmitter.divergence_mrad, s.sensor.transmitter.divergence_el_mrad));
    REQUIRE(m.pointing.size() == 2);
    CHECK(m.pointing[0]);
    CHECK(m.pointing[1]);
}
