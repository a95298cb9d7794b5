// JsonFields: typed, range-checked reading of one scenario object; every failure is an
// InputError naming the file and the full field path.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>

#include "ladarsim/core/input_error.h"
#include "ladarsim/core/json_fields.h"
#include "../support/input_error_of.h"

using ladarsim::InputError;
using ladarsim::JsonFields;
using Catch::Matchers::Contains;
using ladarsim::test::input_error_of;

TEST_CASE("json_fields: a non-object is rejected with its path", "[json_fields]") {
    const auto j = nlohmann::json::parse("[1, 2]");
    const InputError e = input_error_of([&] { JsonFields f(j, "s.json", "objects[1]"); });
    CHECK(e.file() == "s.json");
    CHECK(e.field() == "objects[1]");
    CHECK_THAT(e.problem(), Contains("expected an object") && Contains("array"));
}

TEST_CASE("json_fields: numbers are range checked and the path is complete", "[json_fields]") {
    const auto j = nlohmann::json::parse(R"({"speed_mps": 15, "period_s": -2.5, "name": "x"})");
    JsonFields f(j, "s.json", "objects[2].trajectory");
    CHECK(f.path_of("speed_mps") == "objects[2].trajectory.speed_mps");
    CHECK(f.number("speed_mps", 0.0, 100.0) == 15.0);
    CHECK(f.number("absent_s", 0.0, 100.0, 7.5) == 7.5);  // fallback is not range checked: it is ours

    const InputError below = input_error_of([&] { f.number("period_s", 0.0, 10.0); });
    CHECK(below.field() == "objects[2].trajectory.period_s");
    CHECK_THAT(below.problem(), Contains("-2.5") && Contains("outside [0.0, 10.0]"));

    // The bounds are inclusive.
    CHECK(f.number("speed_mps", 15.0, 15.0) == 15.0);

    const InputError wrong_type = input_error_of([&] { f.number("name", 0.0, 1.0); });
    CHECK(wrong_type.field() == "objects[2].trajectory.name");
    CHECK_THAT(wrong_type.problem(), Contains("expected a number") && Contains("string"));

    const InputError missing = input_error_of([&] { f.number("amplitude_m", 0.0, 1.0); });
    CHECK(missing.field() == "objects[2].trajectory.amplitude_m");
    CHECK_THAT(missing.problem(), Contains("missing"));
}

TEST_CASE("json_fields: infinities cannot come from JSON text, and are refused when built in code", "[json_fields]") {
    // nlohmann refuses to parse an overflowing literal: the scenario reader must turn this
    // exception (out_of_range, not parse_error) into an InputError.
    CHECK_THROWS_AS(nlohmann::json::parse(R"({"range_m": 1e999})"), nlohmann::json::out_of_range);

    nlohmann::json j;
    j["range_m"] = std::numeric_limits<double>::infinity();
    j["position_m"] = {0.0, std::numeric_limits<double>::quiet_NaN(), 1.0};
    JsonFields f(j, "s.json", "sensor");
    CHECK_THAT(input_error_of([&] { f.number("range_m", -1e300, 1e300); }).problem(), Contains("finite"));
    CHECK_THAT(input_error_of([&] { f.vec3("position_m"); }).problem(), Contains("finite"));
}

TEST_CASE("json_fields: whole numbers", "[json_fields]") {
    const auto j = nlohmann::json::parse(
        R"({"id": 3, "float_id": 3.0, "negative": -4, "huge": 18446744073709551615, "big": 9223372036854775807})");
    JsonFields f(j, "s.json", "objects[0]");
    CHECK(f.integer("id", 1, 10) == 3);
    CHECK(f.integer("negative", -10, 10) == -4);
    CHECK(f.integer("big", 0, std::numeric_limits<long long>::max()) == std::numeric_limits<long long>::max());
    CHECK(f.integer("absent", 1, 10, 5) == 5);
    CHECK_THAT(input_error_of([&] { f.integer("float_id", 1, 10); }).problem(), Contains("whole number"));
    CHECK_THAT(input_error_of([&] { f.integer("id", 4, 10); }).problem(), Contains("outside [4, 10]"));
    // 2^64 - 1 is stored unsigned by nlohmann; it must not wrap to -1 and pass a signed range.
    const InputError huge = input_error_of([&] { f.integer("huge", -10, std::numeric_limits<long long>::max()); });
    CHECK(huge.field() == "objects[0].huge");
    CHECK_THAT(huge.problem(), Contains("18446744073709551615"));
}

TEST_CASE("json_fields: strings, booleans, choices", "[json_fields]") {
    const auto j = nlohmann::json::parse(R"({"type": "winding", "jitter": true, "mode": "fast", "flag": 1})");
    JsonFields f(j, "s.json", "render");
    CHECK(f.string("type") == "winding");
    CHECK(f.string("absent", "dflt") == "dflt");
    CHECK(f.boolean("jitter", false));
    CHECK_FALSE(f.boolean("absent_flag", false));
    CHECK_THAT(input_error_of([&] { f.boolean("flag", false); }).problem(), Contains("true or false"));
    CHECK(f.choice("type", {"fixed", "winding"}, "fixed") == "winding");
    CHECK(f.choice("absent_type", {"fixed", "winding"}, "fixed") == "fixed");
    const InputError e = input_error_of([&] { f.choice("mode", {"linear", "smooth"}, "linear"); });
    CHECK(e.field() == "render.mode");
    CHECK_THAT(e.problem(), Contains("\"fast\"") && Contains("linear, smooth"));
}

TEST_CASE("json_fields: vectors, nested objects and arrays", "[json_fields]") {
    const auto j = nlohmann::json::parse(
        R"({"start_m": [1, -2.5, 3e2], "short_m": [1, 2], "text_m": [1, "2", 3], "inner": {"a": 1}, "list": [1]})");
    JsonFields f(j, "s.json", "");
    CHECK(f.vec3("start_m") == Eigen::Vector3d(1.0, -2.5, 300.0));
    CHECK(f.vec3("absent_m", Eigen::Vector3d(4, 5, 6)) == Eigen::Vector3d(4, 5, 6));
    CHECK_THAT(input_error_of([&] { f.vec3("short_m"); }).problem(), Contains("3 numbers"));
    CHECK_THAT(input_error_of([&] { f.vec3("text_m"); }).problem(), Contains("3 numbers"));
    CHECK(f.object("inner").at("a") == 1);
    CHECK(f.array("list").size() == 1);
    CHECK_THAT(input_error_of([&] { f.object("list"); }).problem(), Contains("expected an object"));
    CHECK_THAT(input_error_of([&] { f.array("inner"); }).problem(), Contains("expected an array"));
    // At the top level a key's path is the bare key.
    CHECK(input_error_of([&] { f.number("nothing", 0, 1); }).field() == "nothing");
}

TEST_CASE("json_fields: keys never read are reported with their full path", "[json_fields]") {
    const auto j = nlohmann::json::parse(R"({"speed_mps": 1, "sped_mps": 2})");
    JsonFields f(j, "s.json", "objects[0].trajectory");
    f.number("speed_mps", 0, 10);
    const InputError e = input_error_of([&] { f.reject_unknown_keys(); });
    CHECK(e.field() == "objects[0].trajectory.sped_mps");
    CHECK_THAT(e.problem(), Contains("unknown"));
    CHECK_THAT(std::string(e.what()), Contains("s.json: objects[0].trajectory.sped_mps: "));

    // Reading a key, even one that then fails its check, counts as using it.
    const auto k = nlohmann::json::parse(R"({"a": 1, "b": "x"})");
    JsonFields g(k, "s.json", "x");
    g.number("a", 0, 10);
    CHECK_THROWS_AS(g.number("b", 0, 10), InputError);
    CHECK_NOTHROW(g.reject_unknown_keys());
}

TEST_CASE("json_fields: a misspelt required key is reported as the unknown key it is, with what it meant", "[json_fields]") {
    const auto j = nlohmann::json::parse(R"({"sped_mps": 2, "beams_el": 3, "y": 1})");
    JsonFields f(j, "s.json", "objects[0].trajectory");
    const InputError e = input_error_of([&] { f.number("speed_mps", 0, 10); });
    CHECK(e.field() == "objects[0].trajectory.sped_mps");
    CHECK(e.problem() == "unknown key; did you mean \"speed_mps\"?");
    // Keys two letters apart, or short, are often both valid: the missing one is named.
    CHECK(input_error_of([&] { f.number("beams_az", 0, 10); }).field() == "objects[0].trajectory.beams_az");
    CHECK(input_error_of([&] { f.number("x", 0, 10); }).problem() == "required field is missing");
}

TEST_CASE("json_fields: a null is read only where the key holds null", "[json_fields]") {
    const auto j = nlohmann::json::parse(R"({"class": null, "score": 0.5})");
    JsonFields f(j, "d.json", "tracks[0].objects[1]");
    CHECK(f.null("class"));
    CHECK_FALSE(f.null("score"));
    CHECK_FALSE(f.null("absent"));
    // The null was read; the number was not, and is still unknown until it is.
    CHECK(input_error_of([&] { f.reject_unknown_keys(); }).field() == "tracks[0].objects[1].score");
    f.number("score", 0, 1);
    CHECK_NOTHROW(f.reject_unknown_keys());
}
