// read_ply against PCL's own PLY writer (an independent implementation) and hand-written files for
// what PCL does not write: big-endian data, faces before the vertices, list properties.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <pcl/io/ply_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "ladarsim/core/input_error.h"
#include "ladarsim/scene/ply_file.h"
#include "../support/scratch_dir.h"

using namespace ladarsim::scene;
using ladarsim::InputError;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

pcl::PointCloud<pcl::PointXYZI> sample_cloud() {
    pcl::PointCloud<pcl::PointXYZI> cloud;
    for (int i = 0; i < 50; ++i) {
        pcl::PointXYZI p;
        p.x = 0.25f * static_cast<float>(i) - 3.0f;
        p.y = 1000.5f + static_cast<float>(i * i) * 0.01f;
        p.z = -2.0f + 0.125f * static_cast<float>(i % 7);
        p.intensity = static_cast<float>(i % 11) * 9.5f;
        cloud.push_back(p);
    }
    return cloud;
}

/// Appends `value` as `bytes` big-endian bytes.
template <typename T>
void put_big_endian(std::ofstream& out, T value) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &value, sizeof(T));
    for (std::size_t k = 0; k < sizeof(T); ++k) out.put(static_cast<char>(b[sizeof(T) - 1 - k]));
}

}  // namespace

TEST_CASE("ply_file: PCL's ASCII and binary PLY files read back with every point and field", "[ply_file]") {
    ladarsim::test::ScratchDir dir;
    const auto cloud = sample_cloud();
    for (const bool binary : {false, true}) {
        INFO((binary ? "binary" : "ascii"));
        const fs::path file = dir.path() / (binary ? "b.ply" : "a.ply");
        REQUIRE(pcl::io::savePLYFile(file.string(), cloud, binary) == 0);
        const PlyVertices ply = read_ply(file);
        REQUIRE(ply.count == cloud.size());
        const auto x = ply.property("x"), y = ply.property("y"), z = ply.property("z"), i = ply.property("intensity");
        REQUIRE((x && y && z && i));
        for (std::size_t k = 0; k < cloud.size(); ++k) {
            // PCL writes ASCII floats with enough digits to round-trip a float.
            CHECK(static_cast<float>(ply.value(k, *x)) == cloud[k].x);
            CHECK(static_cast<float>(ply.value(k, *y)) == cloud[k].y);
            CHECK(static_cast<float>(ply.value(k, *z)) == cloud[k].z);
            CHECK(static_cast<float>(ply.value(k, *i)) == cloud[k].intensity);
        }
    }
}

TEST_CASE("ply_file: big-endian vertices after a face element with lists, integer types decoded", "[ply_file]") {
    ladarsim::test::ScratchDir dir;
    const fs::path file = dir.path() / "mesh.ply";
    {
        std::ofstream out(file, std::ios::binary);
        out << "ply\r\nformat binary_big_endian 1.0\r\ncomment faces first\r\nelement face 2\r\n"
               "property list uchar int vertex_indices\r\nelement vertex 3\r\nproperty short x\r\n"
               "property list ushort float normals\r\nproperty double y\r\nproperty uint z\r\nproperty char intensity\r\n"
               "end_header\r\n";
        for (int f = 0; f < 2; ++f) {
            out.put(3);
            for (int k = 0; k < 3; ++k) put_big_endian<std::int32_t>(out, k);
        }
        const std::int16_t xs[] = {-300, 0, 32767};
        const double ys[] = {1.5e6, -0.125, 3.0};
        const std::uint32_t zs[] = {4000000000u, 0u, 7u};
        const std::int8_t is[] = {-5, 0, 127};
        for (int v = 0; v < 3; ++v) {
            put_big_endian<std::int16_t>(out, xs[v]);
            put_big_endian<std::uint16_t>(out, 2);
            put_big_endian<float>(out, 0.5f);
            put_big_endian<float>(out, -0.5f);
            put_big_endian<double>(out, ys[v]);
            put_big_endian<std::uint32_t>(out, zs[v]);
            out.put(static_cast<char>(is[v]));
        }
    }
    const PlyVertices ply = read_ply(file);
    REQUIRE(ply.count == 3);
    REQUIRE(ply.properties == std::vector<std::string>{"x", "y", "z", "intensity"});
    CHECK(ply.value(0, 0) == -300.0);
    CHECK(ply.value(2, 0) == 32767.0);
    CHECK(ply.value(0, 1) == 1.5e6);
    CHECK(ply.value(1, 1) == -0.125);
    CHECK(ply.value(0, 2) == 4000000000.0);
    CHECK(ply.value(2, 2) == 7.0);
    CHECK(ply.value(0, 3) == -5.0);
    CHECK(ply.value(2, 3) == 127.0);
}

TEST_CASE("ply_file: malformed files are refused naming the file and the line or element", "[ply_file]") {
    ladarsim::test::ScratchDir dir;
    const auto refused = [&](const std::string& name, const std::string& text, const std::string& where) {
        INFO(name);
        const fs::path file = dir.path() / name;
        std::ofstream(file, std::ios::binary) << text;
        CHECK_THROWS_WITH(read_ply(file), Contains(name) && Contains(where));
    };
    refused("short.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n1\n2\n", "element vertex");
    refused("format.ply", "ply\nformat binary_middle_endian 1.0\nelement vertex 1\nproperty float x\nend_header\n", "header line 2");
    refused("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n1\n", "header line 4");
    refused("noend.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "end_header");
    refused("novertex.ply", "ply\nformat ascii 1.0\nelement face 0\nend_header\n", "element vertex");
    refused("notply.ply", "PCD v0.7\n", "not a PLY file");
    refused("binshort.ply", std::string("ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nend_header\n") + std::string(5, '\0'),
            "element vertex");
}
