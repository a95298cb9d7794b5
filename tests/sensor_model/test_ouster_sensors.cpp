// The Ouster units as sensors made from their own calibration files, re-rendering what they recorded.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <set>
#include <string>

#include "ladarsim/core/json_file.h"
#include "ladarsim/dataset/ouster_pcap.h"
#include "ladarsim/sensor_model/sensor/ouster_sensor.h"
#include "ladarsim/sensor_model/sensor/sensor.h"
#include "../support/ouster_captures.h"
#include "../support/rerender_recorded.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;
using namespace ladarsim::sensor_model;
using test::kOs1;
using test::kOs2;
using test::Unit;
using test::decode;

TEST_CASE("the Ouster unit as a sensor document points every column and channel where the decoder does", "[ouster]") {
    for (const Unit& u : {kOs1, kOs2}) {
        const auto capture = decode(u);
        if (!capture) return;
        const OusterCalibration& cal = capture->calibration;
        const nlohmann::json doc = ouster_sensor_json(cal);
        const nlohmann::json& scan = doc.at("scan");
        INFO(u.stem << ": " << doc.dump(1).substr(0, 600));
        CHECK(scan.at("pattern") == "channel_table");
        const int columns = scan.at("columns");
        const double first = scan.at("first_column_azimuth_deg");
        const std::vector<double> elevation = scan.at("elevation_deg"), offset = scan.at("azimuth_offset_deg");
        REQUIRE(elevation.size() == static_cast<std::size_t>(cal.pixels_per_column));
        REQUIRE(offset.size() == elevation.size());
        const double deg = M_PI / 180.0;
        double worst_az = 0.0, worst_el = 0.0;
        for (const Return& r : capture->frames.front().returns) {
            const double az = (first - r.column * 360.0 / columns + offset[r.row]) * deg;
            worst_az = std::max(worst_az, std::abs(std::remainder(az - r.beam_az_rad, 2.0 * M_PI)));
            worst_el = std::max(worst_el, std::abs(elevation[r.row] * deg - r.beam_el_rad));
        }
        CHECK(worst_az < 1e-5);  // float beam angles
        CHECK(worst_el < 1e-5);

        // Column 0 fires towards the connector, behind the sensor (Ouster's lidar frame +x).
        CHECK(std::abs(std::remainder(first, 360.0)) == Approx(180.0));
        CHECK(doc.at("scan").at("frame_rate_hz") == 10.0);
        CHECK(doc.at("transmitter").at("wavelength_nm") == 865.0);
        // Each channel's emitter fires once a column: one pulse a beam, 1024 x 10 a second.
        CHECK(doc.at("transmitter").at("pulse_rate_hz") == Approx(1024 * 10));
        CHECK(doc.at("receiver").at("max_range_m") == u.spec_range_m);
        CHECK(doc.at("receiver").at("reported_returns") == "strongest");
        CHECK(doc.at("receiver").at("min_range_m") == 0.8);  // the OS1 datasheet's 0.8 m - 120 m
        const std::string description = doc.at("description");
        CHECK(description.find(std::string(u.stem) + ".json") != std::string::npos);
        CHECK(description.find("estimate") != std::string::npos);
        // The document's shape: these sections and keys, nothing else.
        const std::map<std::string, std::set<std::string>> keys = {
            {"scan", {"pattern", "frame_rate_hz", "columns", "first_column_azimuth_deg", "elevation_deg", "azimuth_offset_deg"}},
            {"transmitter", {"wavelength_nm", "peak_power_w", "pulse_width_ns", "pulse_rate_hz", "divergence_mrad", "divergence_el_mrad"}},
            {"optics", {"aperture_diameter_m", "optics_efficiency", "receiver_fov_mrad", "filter_width_nm"}},
            {"receiver",
             {"responsivity_a_per_w", "apd_gain", "excess_noise_factor", "bandwidth_hz", "dark_current_a", "load_resistance_ohm",
              "temperature_k", "saturation_current_a", "false_alarm_rate_hz", "max_range_m", "min_range_m", "range_folding", "return_gap_m",
              "reported_returns"}},
            {"gimbal", {"az_limit_deg", "el_min_deg", "el_max_deg", "slew_rate_dps"}}};
        std::set<std::string> top;
        for (const auto& item : doc.items()) top.insert(item.key());
        CHECK(top == std::set<std::string>{"name", "description", "scan", "transmitter", "optics", "receiver", "gimbal"});
        for (const auto& [section, expected] : keys) {
            std::set<std::string> found;
            for (const auto& item : doc.at(section).items()) found.insert(item.key());
            CHECK(found == expected);
        }
    }
    if (const auto os1 = decode(kOs1)) CHECK(ouster_sensor_json(os1->calibration).at("name") == "ouster_os-1-32-g");
}

TEST_CASE("an Ouster unit's sensor fires each channel once a column: one pulse a beam", "[ouster]") {
    for (const Unit& u : {kOs1, kOs2}) {
        const auto capture = test::decode(u);
        if (!capture) return;
        const Sensor s = read_sensor(ouster_sensor_json(capture->calibration), u.stem);
        CHECK(s.pulses_per_beam() == Approx(1.0));
        CHECK(s.scan->rows() == capture->calibration.pixels_per_column);
        CHECK(s.scan->columns() == capture->calibration.columns_per_frame);
    }
}

TEST_CASE("each Ouster unit, made from its calibration alone, re-renders its own scene and returns what it recorded", "[ouster]") {
    // As for the VLP-16 (test_velodyne_pcap.cpp): the recorded revolution, as discs facing the
    // lidar's optical centre, is the scene, and the unit fires into it from there. The unit is the
    // sensor file ouster_sensor_json makes from the metadata, named by the scenario as a user
    // names it. Its channel table fires exactly the recorded beams (column = measurement_id, row =
    // channel, directions equal to float precision), so a recorded return is looked for in its
    // own cell; the nearest beam of its row is that cell, 0.35 deg from the next.
    //
    // Measured (RelWithDebInfo, two cores, adaptive footprints):
    //   OS-1-32:  27,033 of 27,105 found (99.73 %), median 7.4 mm; 98 of 195 dark ones; 0.4 s
    //   OS-2-128: 119,602 of 119,676 found (99.94 %), median 11.4 mm; none dark; 2.1 s
    // Missed are far surfaces seen at grazing incidence (31 and 74 beams; cos < 0.25, 19-215 m)
    // under the estimated receiver's threshold, and on the OS-1 41 beams behind the black disc
    // of a reflectivity-0 neighbour. The range residual is the scene's, not the sensor's: the
    // discs are one noisy revolution (up to ~16 and ~23 mm of range noise, from second
    // differences along each ring), neighbouring discs overlap, and the nearest along a beam
    // wins, so rendered ranges come out short (signed medians -7 and -11 mm). Tracing from the
    // optical centre rather than from each beam's true origin, 15.8 or 13.8 mm off the axis,
    // accounts for about 2 mm of the median.
    for (const Unit& u : {kOs1, kOs2}) {
        const auto capture = decode(u);
        if (!capture) return;
        const test::ScratchDir dir;
        write_json(dir / "ouster.json", ouster_sensor_json(capture->calibration));
        const test::RerenderFigures figures =
            test::rerender_recorded(dir, capture->frames.front(), {{"file", "ouster.json"}}, test::ReturnMatching::same_cell());
        INFO(u.stem << ": " << figures);
        CHECK(figures.found >= 0.97 * figures.visible);
        CHECK(figures.median_range_error_m < 0.02);
        // All but the few returns beyond the datasheet's range take part.
        CHECK(figures.visible + figures.dark > 0.99 * u.returns);
    }
}

