// Ground truth and manifest JSON: the layout checked key by key with nlohmann's parser, exact
// round trips, and malformed files reported by field path.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "ladarsim/dataset/ground_truth_file.h"
#include "ladarsim/core/input_error.h"
#include "ladarsim/core/json_file.h"
#include "../support/input_error_of.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;
using ladarsim::test::ScratchDir;

namespace {

GroundTruthObject sample_object(std::uint32_t id) {
    GroundTruthObject o;
    o.object_id = id;
    o.object_class = "drone";
    o.name = "dji-" + std::to_string(id);
    o.time_s = 0.1 + 0.2;  // 0.30000000000000004: needs all 17 digits to come back
    o.returns = 37;
    o.box_world.centre = {1000.0 / 3.0, -2.5, 120.125};
    o.box_world.size = {0.35, 0.35, 0.2};
    o.box_world.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
    o.box_sensor.centre = {990.0, 1e-9, -3.0};
    o.box_sensor.size = o.box_world.size;
    o.box_sensor.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(-0.1, Eigen::Vector3d::UnitZ()));
    return o;
}

std::vector<FrameGroundTruth> sample_truth() {
    FrameGroundTruth empty{0, 0.0, 0.1, {}};
    FrameGroundTruth two{1, 0.1, 0.2, {sample_object(1), sample_object(2)}};
    two.objects[1].object_class = "bird";
    two.objects[1].returns = 0;
    return {empty, two};
}

void check_box(const OrientedBox& got, const OrientedBox& want) {
    CHECK(got.centre == want.centre);
    CHECK(got.size == want.size);
    CHECK(got.orientation.coeffs() == want.orientation.coeffs());
}

std::string contents(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

InputError error_of(const std::filesystem::path& path) {
    return test::input_error_of([&] { read_ground_truth_json(path); });
}

}  // namespace

TEST_CASE("ground_truth_of keeps the frame's index, times and objects", "[ground_truth_file]") {
    Frame frame;
    frame.index = 9;
    frame.start_time_s = 0.9;
    frame.end_time_s = 1.0;
    frame.ground_truth = {sample_object(4)};
    const FrameGroundTruth truth = ground_truth_of(frame);
    CHECK(truth.index == 9);
    CHECK(truth.start_time_s == 0.9);
    CHECK(truth.end_time_s == 1.0);
    REQUIRE(truth.objects.size() == 1);
    CHECK(truth.objects[0].name == "dji-4");
}

TEST_CASE("the file has the documented layout, key by key", "[ground_truth_file]") {
    const ScratchDir dir;
    write_ground_truth_json(dir / "gt.json", sample_truth());
    const auto j = nlohmann::json::parse(contents(dir / "gt.json"));
    REQUIRE(j["frames"].size() == 2);
    CHECK(j["frames"][0]["index"] == 0);
    CHECK(j["frames"][0]["objects"].empty());
    const auto& frame = j["frames"][1];
    CHECK(frame["index"] == 1);
    CHECK(frame["start_time_s"] == 0.1);
    CHECK(frame["end_time_s"] == 0.2);
    const auto& o = frame["objects"][0];
    CHECK(o["id"] == 1);
    CHECK(o["class"] == "drone");
    CHECK(o["name"] == "dji-1");
    CHECK(o["time_s"] == 0.1 + 0.2);
    CHECK(o["returns"] == 37);
    const auto q = sample_object(1).box_world.orientation;
    CHECK(o["box_world"]["centre_m"] == nlohmann::json({1000.0 / 3.0, -2.5, 120.125}));
    CHECK(o["box_world"]["size_m"] == nlohmann::json({0.35, 0.35, 0.2}));
    CHECK(o["box_world"]["orientation_wxyz"] == nlohmann::json({q.w(), q.x(), q.y(), q.z()}));
    CHECK(o["box_sensor"]["centre_m"] == nlohmann::json({990.0, 1e-9, -3.0}));
    CHECK(frame["objects"][1]["class"] == "bird");
}

TEST_CASE("round trip: every value comes back exactly", "[ground_truth_file]") {
    const ScratchDir dir;
    const auto truth = sample_truth();
    write_ground_truth_json(dir / "gt.json", truth);
    const auto read = read_ground_truth_json(dir / "gt.json");
    REQUIRE(read.size() == truth.size());
    for (std::size_t f = 0; f < truth.size(); ++f) {
        CHECK(read[f].index == truth[f].index);
        CHECK(read[f].start_time_s == truth[f].start_time_s);
        CHECK(read[f].end_time_s == truth[f].end_time_s);
        REQUIRE(read[f].objects.size() == truth[f].objects.size());
        for (std::size_t i = 0; i < truth[f].objects.size(); ++i) {
            const auto& got = read[f].objects[i];
            const auto& want = truth[f].objects[i];
            CHECK(got.object_id == want.object_id);
            CHECK(got.object_class == want.object_class);
            CHECK(got.name == want.name);
            CHECK(got.time_s == want.time_s);
            CHECK(got.returns == want.returns);
            check_box(got.box_world, want.box_world);
            check_box(got.box_sensor, want.box_sensor);
        }
    }
    CHECK_FALSE(std::filesystem::exists(dir / "gt.json.tmp"));
}

TEST_CASE("malformed ground truth: InputError naming the file and the field path", "[ground_truth_file]") {
    const ScratchDir dir;
    write_ground_truth_json(dir / "gt.json", sample_truth());
    const auto good = nlohmann::json::parse(contents(dir / "gt.json"));
    const auto path = dir / "bad.json";

    struct Case {
        nlohmann::json::json_pointer pointer;
        nlohmann::json value;  ///< null: remove the field
        std::string field;
    };
    using P = nlohmann::json::json_pointer;
    const Case cases[] = {
        {P("/frames/1/objects/0/box_sensor/size_m"), nullptr, "frames[1].objects[0].box_sensor.size_m"},
        {P("/frames/1/objects/1/id"), "two", "frames[1].objects[1].id"},
        {P("/frames/1/objects/1/id"), -1, "frames[1].objects[1].id"},
        {P("/frames/1/objects/0/box_world/orientation_wxyz"), {1, 0, 0}, "frames[1].objects[0].box_world.orientation_wxyz"},
        {P("/frames/1/objects/0/box_world/orientation_wxyz"), {2, 0, 0, 0}, "frames[1].objects[0].box_world.orientation_wxyz"},
        {P("/frames/1/objects/0/box_world/size_m"), {1, -1, 1}, "frames[1].objects[0].box_world.size_m"},
        {P("/frames/0/end_time_s"), -1.0, "frames[0].end_time_s"},
        {P("/frames/0/objectz"), nlohmann::json::array(), "frames[0].objectz"},
        {P("/frames"), nullptr, "frames"},
    };
    for (const auto& c : cases) {
        INFO(c.field);
        nlohmann::json bad = good;
        if (c.value.is_null()) {
            bad[c.pointer.parent_pointer()].erase(c.pointer.back());
        } else {
            bad[c.pointer] = c.value;
        }
        std::ofstream(path) << bad.dump();
        const InputError e = error_of(path);
        CHECK(e.file() == path.string());
        CHECK(e.field() == c.field);
    }

    std::ofstream(path) << "{\"frames\": [";
    CHECK_THAT(error_of(path).problem(), Catch::Contains("not valid JSON"));
}

TEST_CASE("write_json: pretty, two-space indent, trailing newline", "[ground_truth_file]") {
    const ScratchDir dir;
    write_json(dir / "m.json", {{"a", 1}, {"b", {1, 2}}});
    CHECK(contents(dir / "m.json") == "{\n  \"a\": 1,\n  \"b\": [\n    1,\n    2\n  ]\n}\n");
}
