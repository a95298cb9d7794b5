// Sensors as documents: the bundled presets, a scenario's overrides, a user's own file, and the
// derived quantities people check the paper's numbers with.
#include <catch2/catch.hpp>

#include <fstream>
#include <numbers>

#include "ladarsim/core/input_error.h"
#include "ladarsim/sensor_model/sensor/galvo_raster.h"
#include "ladarsim/sensor_model/render/scenario.h"
#include "ladarsim/sensor_model/sensor/sensor.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;
using namespace ladarsim::sensor_model;
using Catch::Matchers::Contains;

namespace {
void write(const std::filesystem::path& file, const std::string& text) {
    std::ofstream out(file);
    out << text;
}

Scenario scenario_with_sensor(const test::ScratchDir& dir, const std::string& sensor) {
    write(dir / "s.json", R"({"sensor": )" + sensor + "}");
    return load_scenario(dir / "s.json");
}
}  // namespace

TEST_CASE("the paper preset's derived quantities expose the paper's inconsistencies", "[sensor]") {
    const Sensor c = sensor_preset("paper_ladar");
    CHECK(c.scan->frame_scan_duration_s() == Approx(20e-3));
    CHECK(c.scan->beam_dwell_s() == Approx(1e-3 / 150.0));
    // 1 MHz laser over 150 kHz beam positions: 6.67 pulses per beam.
    CHECK(c.pulses_per_beam() == Approx(1e6 / 150e3));
    // c / (2 * 1 MHz) = 149.9 m, far below the 2 km design range.
    CHECK(c.transmitter.unambiguous_range_m() == Approx(149.896229).epsilon(1e-8));
    // Beam pitch 58 urad against a 620 urad divergence: footprints overlap about tenfold.
    CHECK(c.scan->pitch_az_rad() == Approx(0.5 * std::numbers::pi / 180.0 / 150.0));
    CHECK(c.beams_per_second() == Approx(60000.0));
    // 700 kW x 1 ns Gaussian: 0.75 mJ a pulse, 745 W at 1 MHz.
    CHECK(c.transmitter.pulse_energy_j() == Approx(700e3 * 1e-9 * std::sqrt(M_PI / (4 * std::log(2.0)))));
}

TEST_CASE("every bundled sensor reads back from the document it writes", "[sensor]") {
    for (const std::string& name : sensor_presets()) {
        INFO(name);
        const Sensor s = sensor_preset(name);
        CHECK(s.name == name);
        const nlohmann::json written = to_json(s);
        const Sensor again = read_sensor(written, "manifest.json");
        nlohmann::json rewritten = to_json(again);
        CHECK(rewritten == written);
        // What detection reads from a dataset's manifest.
        const auto& d = written.at("derived");
        CHECK(d.at("beams_az").get<int>() == s.scan->columns());
        CHECK(d.at("beams_el").get<int>() == s.scan->rows());
        CHECK(d.at("beam_pitch_el_mrad").get<double>() == Approx(s.scan->pitch_el_rad() * 1e3));
    }
}

TEST_CASE("a scenario overrides single keys of a preset's parts", "[sensor]") {
    test::ScratchDir dir;
    const Scenario s = scenario_with_sensor(
        dir, R"({"preset": "paper_ladar", "position_m": [0, 0, 0], "scan": {"frame_rate_hz": 5},
                 "receiver": {"range_folding": false, "false_alarm_rate_hz": 1000}})");
    const auto& raster = dynamic_cast<const GalvoRaster&>(*s.sensor.scan);
    CHECK(raster.frame_rate_hz() == 5.0);
    CHECK(raster.columns() == 150);  // the rest of the part is the preset's
    CHECK_FALSE(s.sensor.receiver.range_folding);
    CHECK(s.sensor.receiver.false_alarm_rate_hz == 1000.0);
    CHECK(s.sensor.receiver.apd_gain == 10.0);
    CHECK(s.sensor.transmitter.wavelength_nm == 1560.0);
}

TEST_CASE("a misspelt or impossible key names its full path", "[sensor]") {
    test::ScratchDir dir;
    CHECK_THROWS_WITH(scenario_with_sensor(dir, R"({"position_m": [0, 0, 0], "receiver": {"apd_gian": 5}})"),
                      Contains("sensor.receiver.apd_gian"));
    CHECK_THROWS_WITH(scenario_with_sensor(dir, R"({"position_m": [0, 0, 0], "scan": {"beams_az": 0}})"),
                      Contains("sensor.scan.beams_az"));
    CHECK_THROWS_WITH(scenario_with_sensor(dir, R"({"position_m": [0, 0, 0], "scan": {"frame_rate_hz": 100}})"),
                      Contains("sensor.scan.frame_rate_hz") && Contains("longer than the frame period"));
    CHECK_THROWS_WITH(scenario_with_sensor(dir, R"({"position_m": [0, 0, 0], "transmitter": 3})"),
                      Contains("sensor.transmitter"));
    CHECK_THROWS_WITH(scenario_with_sensor(dir, R"({"position_m": [0, 0, 0], "preset": "vlp32"})"),
                      Contains("sensor.preset"));
    CHECK_THROWS_AS(scenario_with_sensor(dir, R"({"position_m": [0, 0, 0], "preset": "paper_ladar", "file": "x.json"})"),
                    InputError);
}

TEST_CASE("a sensor of one's own is one file in the sensor format", "[sensor]") {
    test::ScratchDir dir;
    std::filesystem::create_directories(dir / "sensors");
    // The paper's raster at twice the density, as docs/sensor.md shows it.
    nlohmann::json document = sensor_preset_document("paper_ladar");
    document["name"] = "dense_ladar";
    document["scan"]["beams_az"] = 300;
    document["scan"]["beams_el"] = 40;
    document["scan"]["galvo_rate_hz"] = 2000;
    write(dir / "sensors" / "dense.json", document.dump(2));
    const Scenario s = scenario_with_sensor(dir, R"({"file": "sensors/dense.json", "position_m": [0, 0, 0]})");
    CHECK(s.sensor.name == "dense_ladar");
    CHECK(s.sensor.scan->beam_count() == 12000);
    CHECK(s.sensor.beams_per_second() == Approx(240000.0));

    // Its own mistakes name its own file.
    document["optics"].erase("filter_width_nm");
    write(dir / "sensors" / "dense.json", document.dump(2));
    CHECK_THROWS_WITH(scenario_with_sensor(dir, R"({"file": "sensors/dense.json", "position_m": [0, 0, 0]})"),
                      Contains("dense.json") && Contains("optics.filter_width_nm"));
    CHECK_THROWS_WITH(scenario_with_sensor(dir, R"({"file": "sensors/none.json", "position_m": [0, 0, 0]})"),
                      Contains("none.json"));
}
