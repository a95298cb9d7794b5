// read_manifest: the sensor geometry and per-frame pointing of a manifest, from what the
// renderer writes (sensor_model's to_json) and from hand-written manifests with missing or
// mistyped fields.
#include <catch2/catch.hpp>

#include "ladarsim/core/input_error.h"
#include "ladarsim/core/json_file.h"
#include "ladarsim/dataset/manifest.h"
#include "../support/input_error_of.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;

namespace {

nlohmann::json derived() {
    return {{"beams_az", 1800}, {"beams_el", 16}, {"field_az_deg", 360.0}, {"field_el_deg", 32.0}, {"divergence_mrad", 3.0}};
}

InputError error_of(const std::filesystem::path& file) {
    return test::input_error_of([&] { read_manifest(file); });
}

}  // namespace

TEST_CASE("the geometry from sensor.derived, pointing where a frame has it, and other keys left alone", "[manifest]") {
    const test::ScratchDir dir;
    write_json(dir / "m.json", {{"software", {{"name", "ladarsim"}}},
                                {"sensor", {{"beams_az", 7}, {"derived", derived()}}},
                                {"frames", {{{"index", 0}}, {{"index", 1}, {"gimbal_az_rad", -0.5}, {"gimbal_el_rad", 0.25}}}}});
    const Manifest m = read_manifest(dir / "m.json");
    CHECK(m.sensor.beams_az == 1800);  // derived, not the flat key beside it
    CHECK(m.sensor.beams_el == 16);
    CHECK(m.sensor.field_az_deg == 360.0);
    CHECK(m.sensor.field_el_deg == 32.0);
    CHECK(m.sensor.divergence_mrad == 3.0);
    REQUIRE(m.pointing.size() == 2);
    CHECK_FALSE(m.pointing[0]);
    REQUIRE(m.pointing[1]);
    CHECK(m.pointing[1]->gimbal_az_rad == -0.5);
    CHECK(m.pointing[1]->gimbal_el_rad == 0.25);
}

TEST_CASE("missing or mistyped fields: InputError naming the file and the field", "[manifest]") {
    const test::ScratchDir dir;
    const auto file = dir / "manifest.json";
    CHECK(error_of(file).file() == file.string());
    CHECK(error_of(file).field() == "sensor.derived");
    struct Case {
        nlohmann::json manifest;
        std::string field;
    };
    nlohmann::json zero_beams = derived();
    zero_beams["beams_el"] = 0;
    nlohmann::json no_divergence = derived();
    no_divergence.erase("divergence_mrad");
    const Case cases[] = {
        {{{"frames", nlohmann::json::array()}}, "sensor.derived"},
        {{{"sensor", {{"beams_az", 150}}}, {"frames", nlohmann::json::array()}}, "sensor.derived"},
        {{{"sensor", "paper_ladar"}, {"frames", nlohmann::json::array()}}, "sensor"},
        {{{"sensor", {{"derived", zero_beams}}}, {"frames", nlohmann::json::array()}}, "sensor.derived.beams_el"},
        {{{"sensor", {{"derived", no_divergence}}}, {"frames", nlohmann::json::array()}}, "sensor.derived.divergence_mrad"},
        {{{"sensor", {{"derived", derived()}}}}, "frames"},
        {{{"sensor", {{"derived", derived()}}}, {"frames", {{{"gimbal_az_rad", 0.1}}}}}, "frames[0].gimbal_el_rad"},
        {{{"sensor", {{"derived", derived()}}}, {"frames", {{{"gimbal_az_rad", "left"}, {"gimbal_el_rad", 0}}}}},
         "frames[0].gimbal_az_rad"},
    };
    for (const auto& c : cases) {
        INFO(c.manifest.dump());
        write_json(file, c.manifest);
        const InputError e = error_of(file);
        CHECK(e.file() == file.string());
        CHECK(e.field() == c.field);
    }
}
