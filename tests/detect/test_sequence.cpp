// Loading datasets for detection: the sensor and pointing from the manifest, and clear errors for
// what is missing or malformed.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>

#include "ladarsim/dataset/frame_pcd.h"
#include "ladarsim/core/input_error.h"
#include "ladarsim/core/json_file.h"
#include "ladarsim/detect/sequence.h"
#include "../support/input_error_of.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;

namespace {

/// A manifest as a render writes it, cut to what detection reads: a sensor's derived geometry
/// and two frames, the first with the gimbal pointing 0.1 rad left and 0.05 rad up.
nlohmann::json manifest_json() {
    return {{"sensor",
             {{"preset", "paper_ladar"},
              {"derived",
               {{"beams_az", 150}, {"beams_el", 20}, {"field_az_deg", 0.5}, {"field_el_deg", 0.5},
                {"divergence_mrad", 0.62}, {"beams_per_second", 60000.0}}}}},
            {"frames", {{{"index", 0}, {"gimbal_az_rad", 0.1}, {"gimbal_el_rad", 0.05}}, {{"index", 1}}}}};
}

void write_frames(const std::filesystem::path& dir, int count) {
    std::filesystem::create_directories(dir / "frames");
    Frame frame;
    Return r;
    r.position_sensor = {600.0f, 1.0f, 2.0f};
    frame.returns = {r};
    for (int i = 0; i < count; ++i) write_frame_pcd(dir / "frames" / ("00000" + std::to_string(i) + ".pcd"), frame);
}

}  // namespace

TEST_CASE("a missing, empty or malformed dataset is one InputError naming the file", "[detect]") {
    const test::ScratchDir dir;
    CHECK_THROWS_AS(detect::load_sequence(dir / "nowhere"), InputError);
    std::filesystem::create_directories(dir / "frames");
    try {
        detect::load_sequence(dir.path());
        FAIL("no error for a dataset without frames");
    } catch (const InputError& e) {
        CHECK_THAT(e.what(), Catch::Matchers::Contains("frames"));
    }
    write_json(dir / "manifest.json", manifest_json());
    std::ofstream(dir / "frames" / "000000.pcd") << "this is not a point cloud";
    try {
        detect::load_sequence(dir.path());
        FAIL("no error for a malformed frame");
    } catch (const InputError& e) {
        CHECK_THAT(e.what(), Catch::Matchers::Contains("000000.pcd"));
    }
}

TEST_CASE("the sensor geometry and the gimbal's pointing come from manifest.json", "[detect]") {
    const test::ScratchDir dir;
    write_frames(dir.path(), 2);
    write_json(dir / "manifest.json", manifest_json());
    const detect::Sequence s = detect::load_sequence(dir.path());
    CHECK(s.sensor.beams_az == 150);
    CHECK(s.sensor.beams_el == 20);
    CHECK(s.sensor.field_az_deg == 0.5);
    CHECK(s.sensor.field_el_deg == 0.5);
    CHECK(s.sensor.divergence_mrad == 0.62);
    REQUIRE(s.boresight.size() == 2);
    REQUIRE(s.boresight[0]);
    CHECK(s.boresight[0]->isApprox(Eigen::Vector3d(std::cos(0.05) * std::cos(0.1), std::cos(0.05) * std::sin(0.1), std::sin(0.05))));
    CHECK_FALSE(s.boresight[1]);
}

TEST_CASE("a dataset that does not say which sensor took it: InputError naming manifest.json and sensor.derived",
          "[detect]") {
    const test::ScratchDir dir;
    write_frames(dir.path(), 1);
    const auto manifest = dir / "manifest.json";
    auto error = [&] { return test::input_error_of([&] { detect::load_sequence(dir.path()); }); };
    CHECK(error().file() == manifest.string());
    CHECK(error().field() == "sensor.derived");

    nlohmann::json without_sensor = manifest_json();
    without_sensor.erase("sensor");
    write_json(manifest, without_sensor);
    CHECK(error().file() == manifest.string());
    CHECK(error().field() == "sensor.derived");

    // Today's flat sensor keys are not read: only the derived geometry.
    nlohmann::json flat = manifest_json();
    flat["sensor"] = {{"beams_az", 150}, {"beams_el", 20}, {"field_az_deg", 0.5}, {"field_el_deg", 0.5}};
    write_json(manifest, flat);
    CHECK(error().field() == "sensor.derived");

    nlohmann::json mistyped = manifest_json();
    mistyped["sensor"]["derived"]["beams_el"] = "twenty";
    write_json(manifest, mistyped);
    CHECK(error().field() == "sensor.derived.beams_el");
}
