// The PCD format: every TYPE, SIZE and COUNT in every DATA encoding as PCL writes and reads them
// (an independent implementation of the format), the older header forms PCL still reads, and one
// InputError naming the file and the keyword for anything malformed.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <pcl/PCLPointCloud2.h>
#include <pcl/io/pcd_io.h>

#include "ladarsim/core/input_error.h"
#include "ladarsim/dataset/pcd_file.h"
#include "../support/input_error_of.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;
using ladarsim::test::ScratchDir;

namespace {

void write_text(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

InputError error_of(const std::filesystem::path& path) {
    return test::input_error_of([&] { read_pcd(path); });
}

using PclField = pcl::PCLPointField;

/// Element `element` of field `f` of point `point` of a PCL cloud, as a double.
double pcl_value(const pcl::PCLPointCloud2& cloud, std::size_t point, const PclField& f, int element) {
    const std::uint8_t* p = cloud.data.data() + point * cloud.point_step + f.offset +
                            static_cast<std::size_t>(element) * pcl::getFieldSize(f.datatype);
    auto load = [p](auto v) {
        std::memcpy(&v, p, sizeof v);
        return static_cast<double>(v);
    };
    switch (f.datatype) {
        case PclField::INT8: return load(std::int8_t{});
        case PclField::UINT8: return load(std::uint8_t{});
        case PclField::INT16: return load(std::int16_t{});
        case PclField::UINT16: return load(std::uint16_t{});
        case PclField::INT32: return load(std::int32_t{});
        case PclField::UINT32: return load(std::uint32_t{});
        case PclField::INT64: return load(std::int64_t{});
        case PclField::UINT64: return load(std::uint64_t{});
        case PclField::FLOAT32: return load(float{});
        default: return load(double{});
    }
}

/// An organised `width` x `height` cloud with a field of every PCD TYPE and SIZE, one of COUNT 3,
/// and values that reach each type's limits; point 1 is a beam without a return (NaN x y z).
pcl::PCLPointCloud2 every_type_cloud(std::uint32_t width, std::uint32_t height) {
    pcl::PCLPointCloud2 cloud;
    cloud.width = width;
    cloud.height = height;
    struct Spec {
        const char* name;
        std::uint8_t datatype;
        std::uint32_t count;
    };
    const Spec specs[] = {{"x", PclField::FLOAT32, 1},       {"y", PclField::FLOAT32, 1},     {"z", PclField::FLOAT32, 1},
                          {"range", PclField::FLOAT64, 1},   {"ring", PclField::UINT8, 1},    {"tilt", PclField::INT8, 1},
                          {"column", PclField::UINT16, 1},   {"offset", PclField::INT16, 1},  {"id", PclField::UINT32, 1},
                          {"delta", PclField::INT32, 1},     {"normal", PclField::FLOAT32, 3}, {"stamp", PclField::UINT64, 1},
                          {"shift", PclField::INT64, 1}};
    std::uint32_t offset = 0;
    for (const auto& s : specs) {
        PclField f;
        f.name = s.name;
        f.offset = offset;
        f.datatype = s.datatype;
        f.count = s.count;
        cloud.fields.push_back(f);
        offset += s.count * static_cast<std::uint32_t>(pcl::getFieldSize(s.datatype));
    }
    cloud.point_step = offset;
    cloud.row_step = offset * width;
    cloud.is_dense = false;
    cloud.data.resize(std::size_t{cloud.row_step} * height);
    std::mt19937 rng(11);
    for (std::size_t i = 0; i < std::size_t{width} * height; ++i) {
        std::uint8_t* p = cloud.data.data() + i * offset;
        for (std::uint32_t b = 0; b < offset; ++b) p[b] = static_cast<std::uint8_t>(rng());
        const float nan = std::numeric_limits<float>::quiet_NaN();
        const float xyz[3] = {i == 1 ? nan : 0.125f * i - 3.0f, i == 1 ? nan : -1e5f / (i + 1), i == 1 ? nan : 1234.5678f};
        std::memcpy(p, xyz, sizeof xyz);
        // Floats from random bits may be NaN or infinite, which ascii cannot carry the same way.
        const double range = 1000.00005 + i;
        std::memcpy(p + 12, &range, sizeof range);
        const float normal[3] = {0.6f, -0.8f, 1e-7f * i};
        std::memcpy(p + cloud.fields[10].offset, normal, sizeof normal);
        // Within 2^53, where a double (and so the ascii text PCL writes) still holds every integer.
        const std::uint64_t stamp = (std::uint64_t{1} << 52) + i;
        const std::int64_t shift = -static_cast<std::int64_t>(stamp);
        std::memcpy(p + cloud.fields[11].offset, &stamp, sizeof stamp);
        std::memcpy(p + cloud.fields[12].offset, &shift, sizeof shift);
    }
    return cloud;
}

/// read_pcd's cloud holds exactly what PCL's reader makes of the same file.
void check_as_pcl_reads(const std::filesystem::path& file) {
    pcl::PCLPointCloud2 expected;
    REQUIRE(pcl::io::loadPCDFile(file.string(), expected) == 0);
    const PcdCloud cloud = read_pcd(file);
    REQUIRE(cloud.width() == expected.width);
    REQUIRE(cloud.height() == expected.height);
    REQUIRE(cloud.fields().size() == expected.fields.size());
    for (std::size_t f = 0; f < expected.fields.size(); ++f) {
        const PclField& e = expected.fields[f];
        INFO("field " << e.name);
        REQUIRE(cloud.field(e.name) == f);
        CHECK(cloud.fields()[f].size == static_cast<int>(pcl::getFieldSize(e.datatype)));
        CHECK(cloud.fields()[f].count == static_cast<int>(e.count));
        for (std::uint64_t i = 0; i < cloud.points(); ++i) {
            for (int k = 0; k < static_cast<int>(e.count); ++k) {
                const double want = pcl_value(expected, i, e, k), got = cloud.value(i, f, k);
                if (std::isnan(want)) {
                    CHECK(std::isnan(got));
                } else {
                    CHECK(got == want);
                }
            }
        }
    }
}

const std::string kHeaderStart = "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n";

}  // namespace

TEST_CASE("every TYPE, SIZE and COUNT in ascii, binary and binary_compressed, as PCL writes and reads them", "[pcd_file]") {
    const ScratchDir dir;
    const pcl::PCLPointCloud2 original = every_type_cloud(3, 2);
    pcl::PCDWriter writer;
    REQUIRE(writer.writeASCII((dir / "ascii.pcd").string(), original) == 0);
    REQUIRE(writer.writeBinary((dir / "binary.pcd").string(), original) == 0);
    REQUIRE(writer.writeBinaryCompressed((dir / "compressed.pcd").string(), original) == 0);
    for (const char* name : {"ascii.pcd", "binary.pcd", "compressed.pcd"}) {
        INFO(name);
        check_as_pcl_reads(dir / name);
    }
    // Binary data carries every bit: the values are the original cloud's, NaN points included.
    const PcdCloud compressed = read_pcd(dir / "compressed.pcd");
    CHECK(compressed.data() == std::vector<char>(original.data.begin(), original.data.end()));
    CHECK(std::isnan(compressed.value(1, 0)));
}

TEST_CASE("binary_compressed: a large cloud whose LZF stream is mostly back references", "[pcd_file]") {
    const ScratchDir dir;
    pcl::PCLPointCloud2 cloud = every_type_cloud(5000, 1);
    // Every point as the first but for its x y z, so that the stream is mostly long and
    // overlapping back references.
    for (std::size_t i = 1; i < 5000; ++i) {
        std::memcpy(cloud.data.data() + i * cloud.point_step + 12, cloud.data.data() + 12, cloud.point_step - 12);
    }
    REQUIRE(pcl::PCDWriter().writeBinaryCompressed((dir / "c.pcd").string(), cloud) == 0);
    check_as_pcl_reads(dir / "c.pcd");
}

TEST_CASE("older headers PCL reads: COLUMNS, POINTS alone, no HEIGHT or COUNT, a leading + and Windows line ends",
          "[pcd_file]") {
    const ScratchDir dir;
    write_text(dir / "a.pcd", "# v0.5\r\nCOLUMNS x y z i\r\nSIZE 4 4 8 2\r\nTYPE F F F U\r\nPOINTS 2\r\nDATA ascii\r\n"
                              "1 +2.5 -3e2 7\r\n\r\n4 5 6 +65535\r\n");
    const PcdCloud cloud = read_pcd(dir / "a.pcd");
    REQUIRE(cloud.width() == 2);
    CHECK(cloud.height() == 1);
    CHECK(cloud.value(0, 1) == 2.5);
    CHECK(cloud.value(0, 2) == -300.0);
    CHECK(cloud.value(1, 3) == 65535.0);
    CHECK(cloud.value(0, *cloud.field("i")) == 7.0);
    CHECK_FALSE(cloud.field("intensity"));
}

TEST_CASE("malformed headers: InputError naming the file and the keyword", "[pcd_file]") {
    const ScratchDir dir;
    const auto path = dir / "bad.pcd";
    struct Case {
        std::string text;
        std::string field;
    };
    const Case cases[] = {
        {"GIF89a garbage\x01\x02\n", "header"},
        {kHeaderStart + "WIDTH 1\nHEIGHT 1\nPOINTS 1\n", "DATA"},
        {kHeaderStart + "WIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA zip\n", "DATA"},
        {"FIELDS x y z\nSIZE 4 4\nTYPE F F F\nWIDTH 1\nDATA ascii\n1 2 3\n", "SIZE"},
        {"FIELDS x y z\nSIZE 4 4 2\nTYPE F F F\nWIDTH 1\nDATA ascii\n1 2 3\n", "SIZE"},
        {"FIELDS x y z\nSIZE 4 4 4\nTYPE F F Q\nWIDTH 1\nDATA ascii\n1 2 3\n", "TYPE"},
        {"FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1\nWIDTH 1\nDATA ascii\n1 2 3\n", "COUNT"},
        {"FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 0\nWIDTH 1\nDATA ascii\n1 2 3\n", "COUNT"},
        {"FIELDS x y\nSIZE 4 4\nTYPE F F\nWIDTH 1\nDATA ascii\n1 2\n", "FIELDS"},
        {kHeaderStart + "WIDTH two\nDATA ascii\n", "WIDTH"},
        {kHeaderStart + "WIDTH 2\nHEIGHT 1\nPOINTS 3\nDATA ascii\n", "POINTS"},
        {"FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nDATA ascii\n", "WIDTH"},
        {"FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nHEIGHT 2\nPOINTS 2\nDATA ascii\n", "WIDTH"},
        {kHeaderStart + "WIDTH 4294967296\nHEIGHT 4294967296\nDATA binary\n", "WIDTH"},
    };
    for (const auto& c : cases) {
        INFO(c.text);
        write_text(path, c.text);
        const InputError e = error_of(path);
        CHECK(e.file() == path.string());
        CHECK(e.field() == c.field);
    }
    write_text(path, "FIELDS x y\nSIZE 4 4\nTYPE F F\nWIDTH 1\nDATA ascii\n1 2\n");
    CHECK_THAT(error_of(path).problem(), Catch::Contains("x, y and z"));
}

TEST_CASE("random bytes: InputError naming the file", "[pcd_file]") {
    const ScratchDir dir;
    std::mt19937 rng(7);
    for (int trial = 0; trial < 20; ++trial) {
        std::string bytes(4096, '\0');
        for (char& b : bytes) b = static_cast<char>(rng() & 0xFF);
        if (trial % 2) bytes = kHeaderStart + "WIDTH 100\nDATA binary_compressed\n" + bytes;
        write_text(dir / "garbage.pcd", bytes);
        const InputError e = error_of(dir / "garbage.pcd");
        CHECK(e.file() == (dir / "garbage.pcd").string());
        // The message is for a person: never the file's raw bytes.
        const std::string message = e.what();
        CHECK(std::all_of(message.begin(), message.end(), [](char c) { return c >= 0x20 && c < 0x7f; }));
    }
}

TEST_CASE("truncated or corrupt data: InputError naming DATA", "[pcd_file]") {
    const ScratchDir dir;
    const pcl::PCLPointCloud2 cloud = every_type_cloud(40, 1);
    REQUIRE(pcl::PCDWriter().writeBinaryCompressed((dir / "c.pcd").string(), cloud) == 0);
    std::string compressed;
    {
        std::ifstream in(dir / "c.pcd", std::ios::binary);
        compressed.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    // PCL pads its files to whole pages: the data ends where the sizes before it say.
    const std::size_t stream = compressed.find("DATA binary_compressed\n") + 23;
    std::uint32_t stream_size = 0;
    std::memcpy(&stream_size, compressed.data() + stream, 4);
    const std::string binary_header = kHeaderStart + "WIDTH 1000\nHEIGHT 1\nPOINTS 1000\nDATA binary\n";
    struct Case {
        std::string name;
        std::string bytes;
        std::string problem;
    };
    std::string corrupt = compressed, wrong_size = compressed;
    corrupt[stream + 8] = '\xFF';  // the first control byte: a back reference before the start
    wrong_size[stream + 4] = static_cast<char>(wrong_size[stream + 4] + 1);
    const Case cases[] = {
        {"binary", binary_header + std::string(999 * 12 + 11, '\0'), "truncated"},
        {"compressed", compressed.substr(0, stream + 8 + stream_size - 1), "truncated"},
        {"no sizes", compressed.substr(0, stream + 7), "truncated"},
        {"corrupt", corrupt, "corrupt"},
        {"uncompressed size", wrong_size, "uncompressed"},
        {"ascii", kHeaderStart + "WIDTH 3\nHEIGHT 1\nPOINTS 3\nDATA ascii\n1 2 3\n4 5 6\n", "truncated"},
    };
    for (const auto& c : cases) {
        INFO(c.name);
        write_text(dir / "bad.pcd", c.bytes);
        const InputError e = error_of(dir / "bad.pcd");
        CHECK(e.file() == (dir / "bad.pcd").string());
        CHECK(e.field() == "DATA");
        CHECK_THAT(e.problem(), Catch::Contains(c.problem));
    }
    write_text(dir / "c.pcd", compressed.substr(0, stream + 8 + stream_size));
    check_as_pcl_reads(dir / "c.pcd");
}

TEST_CASE("ascii values that are not numbers of their field's TYPE and SIZE: InputError naming DATA and the point",
          "[pcd_file]") {
    const ScratchDir dir;
    const auto path = dir / "bad.pcd";
    const std::string header = "FIELDS x y z label\nSIZE 4 4 4 4\nTYPE F F F U\nWIDTH 2\nDATA ascii\n";
    for (const std::string data : {"1 2 3 4\n1 2 x 4\n", "1 2 3 4\n1 2 3 -1\n", "1 2 3 4\n1 2 3 4.5\n",
                                   "1 2 3 4\n1 2 3 4294967296\n", "1 2 3 4\n1 2 3\n", "1 2 3 4\n1 2 3 4 5\n",
                                   "1 2 3 4\n1 2 1e39 4\n"}) {
        INFO(data);
        write_text(path, header + data);
        const InputError e = error_of(path);
        CHECK(e.field() == "DATA");
        CHECK_THAT(e.problem(), Catch::Contains("point 1"));
    }
    // Values are counted before the cloud is made: a header promising far more than the lines
    // hold fails at the first line, without memory for a hundred million points.
    write_text(path, "FIELDS x y z d\nSIZE 4 4 4 8\nTYPE F F F F\nCOUNT 1 1 1 65535\nWIDTH 100000000\nDATA ascii\n1 2 3 4\n");
    CHECK_THAT(error_of(path).problem(), Catch::Contains("point 0: too few values"));
    // NaN marks a beam without a return; whole numbers may be written as decimals.
    write_text(path, header + "nan NaN nan 0\n1 2 3 4294967295.0\n");
    const PcdCloud cloud = read_pcd(path);
    CHECK(std::isnan(cloud.value(0, 0)));
    CHECK(cloud.value(1, 3) == 4294967295.0);
}

TEST_CASE("write_pcd: PCL reads every TYPE, SIZE and COUNT back, and so does read_pcd", "[pcd_file]") {
    const ScratchDir dir;
    PcdCloud cloud({{"x", 'F', 4, 1}, {"y", 'F', 8, 1}, {"z", 'I', 1, 1}, {"pair", 'U', 8, 2}, {"code", 'I', 2, 1}}, 2, 2);
    for (std::uint64_t i = 0; i < 4; ++i) {
        cloud.set(i, 0, 0, 0.1 * i);
        cloud.set(i, 1, 0, -1e300 * i);
        cloud.set(i, 2, 0, -128.0 + i);
        cloud.set(i, 3, 0, 9007199254740992.0);
        cloud.set(i, 3, 1, static_cast<double>(i));
        cloud.set(i, 4, 0, -32768.0);
    }
    write_pcd(dir / "w.pcd", cloud);
    CHECK_FALSE(std::filesystem::exists(dir / "w.pcd.tmp"));
    check_as_pcl_reads(dir / "w.pcd");
    const PcdCloud back = read_pcd(dir / "w.pcd");
    CHECK(back.width() == 2);
    CHECK(back.height() == 2);
    CHECK(back.data() == cloud.data());
    CHECK(back.value(3, 0) == static_cast<float>(0.1 * 3));
    CHECK(back.value(2, 3, 1) == 2.0);
}

TEST_CASE("a file that does not exist: InputError", "[pcd_file]") {
    const ScratchDir dir;
    CHECK(error_of(dir / "none.pcd").problem() == "cannot open the point cloud");
}
