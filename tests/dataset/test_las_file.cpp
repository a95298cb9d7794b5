// LAS 1.4 files: what write_las writes read back by read_las, the header fields at the offsets
// the specification gives (read here from the bytes, not through the reader), and files the
// reader refuses.
#include <catch2/catch.hpp>

#include <cstring>
#include <fstream>
#include <iterator>

#include "ladarsim/core/input_error.h"
#include "ladarsim/dataset/las_file.h"
#include "../support/input_error_of.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;

namespace {

LasCloud two_points() {
    LasCloud cloud;
    cloud.system_identifier = "test";
    cloud.generating_software = "ladarsim tests";
    cloud.offset = Eigen::Vector3d(100.0, -50.0, 0.0);
    cloud.extra_fields = {{"object_id", LasExtraField::Type::uint32, "id", true, 4294967295.0},
                          {"intensity_pe", LasExtraField::Type::float32, "pe", false, 0.0}};
    LasPoint a;
    a.position = {101.23456, -49.5, 12.0001};
    a.intensity = 65535;
    a.return_number = 1;
    a.number_of_returns = 2;
    a.classification = 64;
    a.user_data = 1;
    a.scan_angle = -1234;
    a.gps_time = 12.345678901234;
    a.extra = {7.0, 1234.5};
    LasPoint b = a;
    b.position = {90.0, -60.00004, -3.0};
    b.return_number = 2;
    b.classification = 2;
    b.extra = {4294967295.0, -0.25};
    cloud.points = {a, b};
    return cloud;
}

std::string bytes_of(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

template <typename T>
T at(const std::string& bytes, std::size_t offset) {
    T value;
    std::memcpy(&value, bytes.data() + offset, sizeof value);
    return value;
}

}  // namespace

TEST_CASE("a LAS file reads back as the cloud written, positions to the scale", "[las]") {
    test::ScratchDir dir;
    const LasCloud written = two_points();
    write_las(dir / "a.las", written);
    const LasCloud read = read_las(dir / "a.las");
    CHECK(read.system_identifier == "test");
    CHECK(read.generating_software == "ladarsim tests");
    CHECK(read.offset == written.offset);
    REQUIRE(read.extra_fields.size() == 2);
    CHECK(read.extra_fields[0].name == "object_id");
    CHECK(read.extra_fields[0].has_no_data);
    CHECK(read.extra_fields[0].no_data == 4294967295.0);
    CHECK(read.extra_fields[1].type == LasExtraField::Type::float32);
    REQUIRE(read.points.size() == 2);
    for (std::size_t i = 0; i < 2; ++i) {
        const LasPoint &w = written.points[i], &r = read.points[i];
        CHECK((r.position - w.position).cwiseAbs().maxCoeff() <= 0.5e-4 + 1e-9);
        CHECK(r.intensity == w.intensity);
        CHECK(r.return_number == w.return_number);
        CHECK(r.number_of_returns == w.number_of_returns);
        CHECK(r.classification == w.classification);
        CHECK(r.user_data == w.user_data);
        CHECK(r.scan_angle == w.scan_angle);
        CHECK(r.gps_time == w.gps_time);
        CHECK(r.extra == w.extra);
    }
}

TEST_CASE("a LAS file's header holds format 6, the counts by return and the bounds where LAS 1.4 puts them", "[las]") {
    test::ScratchDir dir;
    write_las(dir / "a.las", two_points());
    const std::string b = bytes_of(dir / "a.las");
    CHECK(b.compare(0, 4, "LASF") == 0);
    CHECK(at<std::uint8_t>(b, 24) == 1);
    CHECK(at<std::uint8_t>(b, 25) == 4);
    CHECK((at<std::uint16_t>(b, 6) & 0x10) != 0);  // WKT bit, required for format 6
    CHECK(at<std::uint16_t>(b, 94) == 375);
    CHECK(at<std::uint32_t>(b, 96) == 375 + 54 + 2 * 192);
    CHECK(at<std::uint32_t>(b, 100) == 1);
    CHECK(at<std::uint8_t>(b, 104) == 6);
    CHECK(at<std::uint16_t>(b, 105) == 30 + 8);
    CHECK(at<std::uint32_t>(b, 107) == 0);  // legacy count
    CHECK(at<std::uint64_t>(b, 247) == 2);
    CHECK(at<std::uint64_t>(b, 255) == 1);  // first returns
    CHECK(at<std::uint64_t>(b, 263) == 1);  // second returns
    CHECK(at<double>(b, 179) == Approx(101.2346));  // max x
    CHECK(at<double>(b, 187) == Approx(90.0));      // min x
    CHECK(b.compare(375 + 2, 9, "LASF_Spec") == 0);
    CHECK(at<std::uint16_t>(b, 375 + 18) == 4);
    CHECK(b.size() == 375 + 54 + 2 * 192 + 2 * 38);
}

TEST_CASE("a LAS file is the same bytes each time it is written", "[las]") {
    test::ScratchDir dir;
    write_las(dir / "a.las", two_points());
    write_las(dir / "b.las", two_points());
    CHECK(bytes_of(dir / "a.las") == bytes_of(dir / "b.las"));
}

TEST_CASE("write_las refuses a position beyond the int32 range and a return number outside 1 to 15", "[las]") {
    test::ScratchDir dir;
    LasCloud far = two_points();
    far.points[0].position.x() = 1e6;  // 900 km from the offset at 0.1 mm
    CHECK(test::input_error_of([&] { write_las(dir / "far.las", far); }).field() == "points.x");
    LasCloud sixteen = two_points();
    sixteen.points[1].number_of_returns = 16;
    CHECK(test::input_error_of([&] { write_las(dir / "n.las", sixteen); }).field() == "points.return_number");
    CHECK(!std::filesystem::exists(dir / "far.las"));
}

TEST_CASE("read_las refuses a file that is not LAS 1.4 format 6 or is cut short", "[las]") {
    test::ScratchDir dir;
    write_las(dir / "a.las", two_points());
    const std::string good = bytes_of(dir / "a.las");
    const auto write = [&](const std::string& name, const std::string& bytes) {
        std::ofstream(dir / name, std::ios::binary) << bytes;
        return dir / name;
    };
    CHECK(test::input_error_of([&] { read_las(write("text.las", "hello")); }).field() == "header");
    std::string format7 = good;
    format7[104] = 7;
    CHECK(test::input_error_of([&] { read_las(write("f7.las", format7)); }).field() == "header.point_data_format");
    CHECK(test::input_error_of([&] { read_las(write("cut.las", good.substr(0, good.size() - 5))); }).field() == "points");
}
