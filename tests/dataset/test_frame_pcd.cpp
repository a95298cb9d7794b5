// Frames as PCD: the layout checked against the PCD v0.7 specification written out by hand and
// against PCL's own reader and writer (an independent implementation of the format); recorded
// clouds read into returns.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include <pcl/PCLPointCloud2.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "ladarsim/core/input_error.h"
#include "ladarsim/dataset/frame_pcd.h"
#include "../support/input_error_of.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;
using ladarsim::test::ScratchDir;

namespace {

/// Three returns whose values exercise every field: a double range no float can hold, the
/// largest U2/U1/U4 values, negative coordinates and angles.
Frame sample_frame() {
    Frame frame;
    frame.index = 7;
    frame.columns = 150;
    frame.rows = 20;
    Return a;
    a.position_sensor = {12.5f, -3.25f, 1.125f};
    a.intensity = 0.75f;
    a.range_m = 12.999999999999998;
    a.time_s = 1.0000000123;
    a.beam_az_rad = 0.001f;
    a.beam_el_rad = -0.002f;
    a.column = 3;
    a.row = 1;
    a.return_index = 0;
    a.object_id = 7;
    a.snr = 12.25f;
    Return b = a;
    b.position_sensor = {20.0f, -5.0f, 1.8f};
    b.range_m = 20.8;
    b.return_index = 1;
    b.object_id = 0;
    Return c;
    c.position_sensor = {1000.0f, 0.1f, -0.3f};
    c.intensity = 1e-7f;
    c.range_m = 1000.00005;
    c.time_s = 2.5e-3;
    c.beam_az_rad = -0.004f;
    c.beam_el_rad = 0.004f;
    c.column = 65535;
    c.row = 19;
    c.return_index = 255;
    c.object_id = 0xFFFFFFFFu;
    c.snr = 5.5f;
    c.source = ReturnSource::false_alarm;
    c.pulse_offset = 255;
    c.saturated = true;
    frame.returns = {a, b, c};
    return frame;
}

template <typename T>
bool same_bits(T a, T b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

void check_identical(const Return& got, const Return& want) {
    for (int i = 0; i < 3; ++i) CHECK(same_bits(got.position_sensor[i], want.position_sensor[i]));
    CHECK(same_bits(got.intensity, want.intensity));
    CHECK(same_bits(got.range_m, want.range_m));
    CHECK(same_bits(got.time_s, want.time_s));
    CHECK(same_bits(got.beam_az_rad, want.beam_az_rad));
    CHECK(same_bits(got.beam_el_rad, want.beam_el_rad));
    CHECK(got.column == want.column);
    CHECK(got.row == want.row);
    CHECK(got.return_index == want.return_index);
    CHECK(got.object_id == want.object_id);
    CHECK(same_bits(got.snr, want.snr));
    CHECK(got.source == want.source);
    CHECK(got.pulse_offset == want.pulse_offset);
    CHECK(got.saturated == want.saturated);
}

std::string contents(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_text(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

template <typename T>
T at(const pcl::PCLPointCloud2& cloud, int point, int offset) {
    T value;
    std::memcpy(&value, cloud.data.data() + point * cloud.point_step + offset, sizeof value);
    return value;
}

InputError error_of(const std::filesystem::path& path) {
    return test::input_error_of([&] { read_frame_pcd(path); });
}

}  // namespace

TEST_CASE("the header is PCD v0.7 as specified and the data 56 packed bytes a point", "[frame_pcd]") {
    const ScratchDir dir;
    write_frame_pcd(dir / "f.pcd", sample_frame());
    const std::string header =
        "# .PCD v0.7 - Point Cloud Data file format\n"
        "VERSION 0.7\n"
        "FIELDS x y z intensity range_m time_s beam_az beam_el column row return_index object_id snr source "
        "pulse_offset saturated\n"
        "SIZE 4 4 4 4 8 8 4 4 2 2 1 4 4 1 1 1\n"
        "TYPE F F F F F F F F U U U U F U U U\n"
        "COUNT 1 1 1 1 1 1 1 1 1 1 1 1 1 1 1 1\n"
        "WIDTH 3\n"
        "HEIGHT 1\n"
        "VIEWPOINT 0 0 0 1 0 0 0\n"
        "POINTS 3\n"
        "DATA binary\n";
    const std::string bytes = contents(dir / "f.pcd");
    REQUIRE(bytes.size() == header.size() + 3 * 56);
    CHECK(bytes.substr(0, header.size()) == header);
    // Point 2's object_id (bytes 45-48 of its 56, little-endian), then its source (2), pulse offset
    // (255) and saturation flag (1).
    CHECK(bytes.substr(bytes.size() - 11, 4) == std::string(4, '\xFF'));
    CHECK(bytes.substr(bytes.size() - 3) == std::string("\x02\xFF\x01"));
}

TEST_CASE("round trip: every field of every return comes back bit-identical", "[frame_pcd]") {
    const ScratchDir dir;
    const Frame frame = sample_frame();
    write_frame_pcd(dir / "f.pcd", frame);
    const auto returns = read_frame_pcd(dir / "f.pcd");
    REQUIRE(returns.size() == frame.returns.size());
    for (std::size_t i = 0; i < returns.size(); ++i) check_identical(returns[i], frame.returns[i]);
    CHECK_FALSE(std::filesystem::exists(dir / "f.pcd.tmp"));
}

TEST_CASE("PCL reads our file: width, field layout and values decoded by hand", "[frame_pcd]") {
    const ScratchDir dir;
    const Frame frame = sample_frame();
    write_frame_pcd(dir / "f.pcd", frame);
    pcl::PCLPointCloud2 cloud;
    REQUIRE(pcl::io::loadPCDFile((dir / "f.pcd").string(), cloud) == 0);
    CHECK(cloud.width == 3);
    CHECK(cloud.height == 1);
    CHECK(cloud.point_step == 56);

    struct Expected {
        const char* name;
        std::uint8_t datatype;
        std::uint32_t offset;
    };
    using F = pcl::PCLPointField;
    const Expected expected[] = {
        {"x", F::FLOAT32, 0},        {"y", F::FLOAT32, 4},        {"z", F::FLOAT32, 8},
        {"intensity", F::FLOAT32, 12}, {"range_m", F::FLOAT64, 16}, {"time_s", F::FLOAT64, 24},
        {"beam_az", F::FLOAT32, 32}, {"beam_el", F::FLOAT32, 36}, {"column", F::UINT16, 40},
        {"row", F::UINT16, 42},      {"return_index", F::UINT8, 44}, {"object_id", F::UINT32, 45},
        {"snr", F::FLOAT32, 49},     {"source", F::UINT8, 53},     {"pulse_offset", F::UINT8, 54},
        {"saturated", F::UINT8, 55},
    };
    REQUIRE(cloud.fields.size() == std::size(expected));
    for (std::size_t i = 0; i < std::size(expected); ++i) {
        INFO("field " << i);
        CHECK(cloud.fields[i].name == expected[i].name);
        CHECK(cloud.fields[i].datatype == expected[i].datatype);
        CHECK(cloud.fields[i].offset == expected[i].offset);
        CHECK(cloud.fields[i].count == 1);
    }

    CHECK(at<float>(cloud, 0, 0) == 12.5f);
    CHECK(at<float>(cloud, 0, 4) == -3.25f);
    CHECK(at<double>(cloud, 0, 16) == 12.999999999999998);
    CHECK(at<double>(cloud, 0, 24) == 1.0000000123);
    CHECK(at<std::uint16_t>(cloud, 0, 40) == 3);
    CHECK(at<std::uint16_t>(cloud, 0, 42) == 1);
    CHECK(at<std::uint8_t>(cloud, 1, 44) == 1);
    CHECK(at<std::uint32_t>(cloud, 0, 45) == 7);
    CHECK(at<float>(cloud, 2, 0) == 1000.0f);
    CHECK(at<double>(cloud, 2, 16) == 1000.00005);
    CHECK(at<std::uint16_t>(cloud, 2, 40) == 65535);
    CHECK(at<std::uint8_t>(cloud, 2, 44) == 255);
    CHECK(at<std::uint32_t>(cloud, 2, 45) == 0xFFFFFFFFu);
    CHECK(at<float>(cloud, 0, 49) == 12.25f);
    CHECK(at<std::uint8_t>(cloud, 2, 53) == 2);
    CHECK(at<std::uint8_t>(cloud, 2, 54) == 255);
    CHECK(at<std::uint8_t>(cloud, 2, 55) == 1);
    CHECK(at<std::uint8_t>(cloud, 1, 55) == 0);
}

TEST_CASE("an empty frame is a valid PCD with no points", "[frame_pcd]") {
    const ScratchDir dir;
    Frame empty;
    empty.columns = 150;
    empty.rows = 20;
    write_frame_pcd(dir / "empty.pcd", empty);
    CHECK(read_frame_pcd(dir / "empty.pcd").empty());
    pcl::PCLPointCloud2 cloud;
    REQUIRE(pcl::io::loadPCDFile((dir / "empty.pcd").string(), cloud) == 0);
    CHECK(cloud.width == 0);
    CHECK(cloud.fields.size() == 16);
    CHECK(cloud.data.empty());
}

TEST_CASE("recorded clouds written by PCL: binary, ascii and compressed x y z intensity, NaN points skipped", "[frame_pcd]") {
    const ScratchDir dir;
    // An organised 2 x 2 cloud with one beam that had no return, as PCL marks it.
    pcl::PointCloud<pcl::PointXYZI> recorded(2, 2);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    recorded.at(0, 0) = pcl::PointXYZI(0.5f);
    recorded.at(0, 0).x = 10.0f;
    recorded.at(0, 0).y = -1.5f;
    recorded.at(0, 0).z = 0.25f;
    recorded.at(1, 0).x = recorded.at(1, 0).y = recorded.at(1, 0).z = nan;
    recorded.at(0, 1).x = 11.0f;
    recorded.at(0, 1).intensity = 2.0f;
    recorded.at(1, 1).z = -7.0f;
    recorded.is_dense = false;
    REQUIRE(pcl::io::savePCDFileBinary((dir / "binary.pcd").string(), recorded) == 0);
    REQUIRE(pcl::io::savePCDFileASCII((dir / "ascii.pcd").string(), recorded) == 0);
    REQUIRE(pcl::io::savePCDFileBinaryCompressed((dir / "compressed.pcd").string(), recorded) == 0);

    for (const char* name : {"binary.pcd", "ascii.pcd", "compressed.pcd"}) {
        INFO(name);
        const auto returns = read_frame_pcd(dir / name);
        REQUIRE(returns.size() == 3);
        CHECK(returns[0].position_sensor == Eigen::Vector3f(10.0f, -1.5f, 0.25f));
        CHECK(returns[0].intensity == 0.5f);
        CHECK(returns[1].position_sensor == Eigen::Vector3f(11.0f, 0.0f, 0.0f));
        CHECK(returns[1].intensity == 2.0f);
        CHECK(returns[2].position_sensor == Eigen::Vector3f(0.0f, 0.0f, -7.0f));
        // Fields the recording lacks stay at their defaults.
        CHECK(returns[2].range_m == 0.0);
        CHECK(returns[2].object_id == 0);
    }
}

TEST_CASE("hand-written ascii: x y z only, an extra field, Windows line ends", "[frame_pcd]") {
    const ScratchDir dir;
    write_text(dir / "a.pcd",
               "# recorded\r\nVERSION .7\r\nFIELDS x y z label\r\nSIZE 8 8 8 4\r\nTYPE F F F U\r\n"
               "COUNT 1 1 1 1\r\nWIDTH 2\r\nHEIGHT 1\r\nPOINTS 2\r\nDATA ascii\r\n"
               "1.5 -2 3e2 9\r\n0.1 0.2 0.3 4\r\n");
    const auto returns = read_frame_pcd(dir / "a.pcd");
    REQUIRE(returns.size() == 2);
    CHECK(returns[0].position_sensor == Eigen::Vector3f(1.5f, -2.0f, 300.0f));
    CHECK(returns[1].position_sensor == Eigen::Vector3f(0.1f, 0.2f, 0.3f));
    CHECK(returns[1].object_id == 0);  // "label" is not object_id
}

TEST_CASE("a Return field with several elements: InputError naming COUNT", "[frame_pcd]") {
    const ScratchDir dir;
    write_text(dir / "a.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 3\nWIDTH 1\nDATA ascii\n1 2 3 4 5\n");
    const InputError e = error_of(dir / "a.pcd");
    CHECK(e.file() == (dir / "a.pcd").string());
    CHECK(e.field() == "COUNT");
    // A field the frame has no place for may have any COUNT.
    write_text(dir / "b.pcd", "FIELDS x y z normal\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 3\nWIDTH 1\nDATA ascii\n1 2 3 4 5 6\n");
    CHECK(read_frame_pcd(dir / "b.pcd").size() == 1);
}

TEST_CASE("a value that fits the file's TYPE but not the Return's: InputError naming DATA and the point", "[frame_pcd]") {
    const ScratchDir dir;
    const std::string header = "FIELDS x y z column object_id\nSIZE 4 4 4 4 8\nTYPE F F F F I\nWIDTH 2\nDATA ascii\n";
    for (const std::string data : {"1 2 3 4 5\n1 2 3 4.5 5\n", "1 2 3 4 5\n1 2 3 65536 5\n", "1 2 3 4 5\n1 2 3 4 -1\n",
                                   "1 2 3 4 5\n1 2 3 4 4294967296\n"}) {
        INFO(data);
        write_text(dir / "a.pcd", header + data);
        const InputError e = error_of(dir / "a.pcd");
        CHECK(e.field() == "DATA");
        CHECK_THAT(e.problem(), Catch::Contains("point 1"));
    }
    write_text(dir / "a.pcd", header + "1 2 3 4 5\n1 2 3 65535 4294967295\n");
    const auto returns = read_frame_pcd(dir / "a.pcd");
    REQUIRE(returns.size() == 2);
    CHECK(returns[1].column == 65535);
    CHECK(returns[1].object_id == 4294967295u);
}
