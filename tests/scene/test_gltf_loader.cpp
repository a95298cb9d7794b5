// load_gltf on glTF files built here byte by byte, so every expected vertex is worked out by hand.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladarsim/core/input_error.h"
#include "ladarsim/scene/gltf_loader.h"
#include "../support/scratch_dir.h"
#include "../support/shared_data.h"
#include "../support/skip.h"

using namespace ladarsim;
using nlohmann::json;

namespace {

std::string base64(const std::vector<unsigned char>& bytes) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const unsigned n = (bytes[i] << 16) | ((i + 1 < bytes.size() ? bytes[i + 1] : 0) << 8) |
                           (i + 2 < bytes.size() ? bytes[i + 2] : 0);
        out += table[(n >> 18) & 63];
        out += table[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? table[n & 63] : '=';
    }
    return out;
}

/// A glTF document with one binary buffer, assembled accessor by accessor.
struct GltfBuilder {
    json doc = {{"asset", {{"version", "2.0"}}}, {"accessors", json::array()}, {"bufferViews", json::array()},
                {"meshes", json::array()}, {"nodes", json::array()}, {"materials", json::array()}};
    std::vector<unsigned char> bin;

    int add_view(const void* data, std::size_t size) {
        while (bin.size() % 4) bin.push_back(0);
        const std::size_t offset = bin.size();
        bin.resize(offset + size);
        std::memcpy(bin.data() + offset, data, size);
        doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}});
        return static_cast<int>(doc["bufferViews"].size()) - 1;
    }

    int positions(const std::vector<float>& xyz) {
        const int view = add_view(xyz.data(), xyz.size() * sizeof(float));
        doc["accessors"].push_back({{"bufferView", view}, {"componentType", 5126}, {"count", xyz.size() / 3}, {"type", "VEC3"}});
        return static_cast<int>(doc["accessors"].size()) - 1;
    }

    int indices(const std::vector<std::uint16_t>& idx) {
        const int view = add_view(idx.data(), idx.size() * sizeof(std::uint16_t));
        doc["accessors"].push_back({{"bufferView", view}, {"componentType", 5123}, {"count", idx.size()}, {"type", "SCALAR"}});
        return static_cast<int>(doc["accessors"].size()) - 1;
    }

    /// A mesh of one primitive; indices < 0 means non-indexed, material < 0 means none.
    int mesh(int position_accessor, int index_accessor, int material = -1) {
        json primitive = {{"attributes", {{"POSITION", position_accessor}}}};
        if (index_accessor >= 0) primitive["indices"] = index_accessor;
        if (material >= 0) primitive["material"] = material;
        doc["meshes"].push_back({{"primitives", {primitive}}});
        return static_cast<int>(doc["meshes"].size()) - 1;
    }

    int node(json n) {
        doc["nodes"].push_back(std::move(n));
        return static_cast<int>(doc["nodes"].size()) - 1;
    }

    json finished() const {
        json d = doc;
        if (!bin.empty())
            d["buffers"] = {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
        if (!d.contains("scenes")) {
            json roots = json::array();
            for (std::size_t i = 0; i < d["nodes"].size(); ++i) roots.push_back(i);
            d["scenes"] = {{{"nodes", roots}}};
            d["scene"] = 0;
        }
        return d;
    }

    std::filesystem::path write_gltf(const std::filesystem::path& file) const {
        std::ofstream(file) << finished().dump();
        return file;
    }

    /// The same document as a GLB container: JSON chunk, then the buffer as the BIN chunk.
    std::filesystem::path write_glb(const std::filesystem::path& file) const {
        json d = finished();
        d["buffers"] = {{{"byteLength", bin.size()}}};
        std::string text = d.dump();
        while (text.size() % 4) text += ' ';
        std::vector<unsigned char> body = bin;
        while (body.size() % 4) body.push_back(0);
        auto u32 = [](std::ofstream& out, std::uint32_t v) { out.write(reinterpret_cast<const char*>(&v), 4); };
        std::ofstream out(file, std::ios::binary);
        out.write("glTF", 4);
        u32(out, 2);
        u32(out, static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + body.size()));
        u32(out, static_cast<std::uint32_t>(text.size()));
        out.write("JSON", 4);
        out.write(text.data(), static_cast<std::streamsize>(text.size()));
        u32(out, static_cast<std::uint32_t>(body.size()));
        out.write("BIN\0", 4);
        out.write(reinterpret_cast<const char*>(body.data()), static_cast<std::streamsize>(body.size()));
        return file;
    }
};

const std::vector<float> kUnitTriangle = {1, 0, 0, 0, 1, 0, 0, 0, 1};

Eigen::Vector3f vertex(const scene::Model& m, std::size_t triangle, int corner) {
    return m.mesh.positions[m.mesh.triangles[triangle][static_cast<std::size_t>(corner)]];
}

}  // namespace

TEST_CASE("node transforms compose down the hierarchy and land where hand computation says", "[gltf]") {
    test::ScratchDir dir;
    GltfBuilder b;
    const int mesh = b.mesh(b.positions(kUnitTriangle), b.indices({0, 1, 2}));
    // Child: a column-major matrix = translate(0, 0, 5) * scale(2).
    const int child = b.node({{"mesh", mesh}, {"matrix", {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 5, 1}}});
    // Root: translate(1, 2, 3) * rotate 90 deg about y, which maps (x, y, z) to (z, y, -x).
    const double s = std::sqrt(0.5);
    b.node({{"children", {child}}, {"translation", {1, 2, 3}}, {"rotation", {0, s, 0, s}}});
    b.doc["scenes"] = {{{"nodes", {1}}}};
    b.doc["scene"] = 0;

    const scene::Model m = scene::load_gltf(b.write_gltf(dir.path() / "hierarchy.gltf"));
    REQUIRE(m.mesh.triangles.size() == 1);
    // (1,0,0) -> child (2,0,5) -> rotated (5,0,-2) -> translated (6,2,1) -> model (z,x,y) = (1,6,2).
    // (0,1,0) -> (0,2,5) -> (5,2,0) -> (6,4,3) -> (3,6,4).   (0,0,1) -> (0,0,7) -> (7,0,0) -> (8,2,3) -> (3,8,2).
    const Eigen::Vector3f expected[3] = {{1, 6, 2}, {3, 6, 4}, {3, 8, 2}};
    for (int k = 0; k < 3; ++k) CHECK((vertex(m, 0, k) - expected[k]).norm() < 1e-5f);
}

TEST_CASE("several instances of one mesh, indexed and non-indexed primitives", "[gltf]") {
    test::ScratchDir dir;
    GltfBuilder b;
    const int indexed = b.mesh(b.positions(kUnitTriangle), b.indices({0, 1, 2}));
    const int plain = b.mesh(b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 5, 6, 5, 5, 5, 6, 5}), -1);
    b.node({{"mesh", indexed}, {"translation", {10, 0, 0}}});
    b.node({{"mesh", indexed}, {"translation", {20, 0, 0}}});
    b.node({{"mesh", plain}});

    const scene::Model m = scene::load_gltf(b.write_gltf(dir.path() / "instances.gltf"));
    REQUIRE(m.mesh.triangles.size() == 4);
    // glTF x is model y: the two instances sit 10 and 20 m to the model's left.
    CHECK(vertex(m, 0, 0).isApprox(Eigen::Vector3f(0, 11, 0)));
    CHECK(vertex(m, 1, 0).isApprox(Eigen::Vector3f(0, 21, 0)));
    CHECK(vertex(m, 3, 0).isApprox(Eigen::Vector3f(5, 5, 5)));
}

TEST_CASE(".glb and .gltf of the same document load identically", "[gltf]") {
    test::ScratchDir dir;
    GltfBuilder b;
    b.doc["materials"].push_back({{"name", "paint"}, {"extras", {{"ladar", {{"reflectance", 0.7}}}}}});
    const int mesh = b.mesh(b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}), b.indices({0, 1, 2, 2, 1, 3}), 0);
    b.node({{"mesh", mesh}, {"scale", {1, 2, 3}}, {"translation", {0.5, -1, 4}}});

    const scene::Model a = scene::load_gltf(b.write_gltf(dir.path() / "same.gltf"));
    const scene::Model g = scene::load_gltf(b.write_glb(dir.path() / "same.glb"));
    REQUIRE(a.mesh.positions == g.mesh.positions);
    REQUIRE(a.mesh.triangles == g.mesh.triangles);
    REQUIRE(a.mesh.triangle_material == g.mesh.triangle_material);
    REQUIRE(a.materials.size() == 1);
    CHECK(g.materials[0].name == "paint");
    CHECK(g.materials[0].reflectance == 0.7);
}

TEST_CASE("degenerate and non-finite triangles are dropped and counted", "[gltf]") {
    test::ScratchDir dir;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    GltfBuilder b;
    const int mesh = b.mesh(b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0,   // 0-2: a good triangle
                                         2, 0, 0,                     // 3: collinear with 0 and 1
                                         nan, 0, 0, 0, inf, 0}),      // 4, 5: non-finite
                            b.indices({0, 1, 2, 0, 1, 1, 0, 1, 3, 0, 4, 2, 5, 1, 2, 2, 1, 0}));
    b.node({{"mesh", mesh}});
    scene::GltfLoadReport report;
    const scene::Model m = scene::load_gltf(b.write_gltf(dir.path() / "dirty.gltf"), &report);
    CHECK(report.triangles_loaded == 2);   // the good one and its reverse
    CHECK(report.degenerate_dropped == 2); // repeated index, collinear
    CHECK(report.nonfinite_dropped == 2);
    REQUIRE(m.mesh.triangles.size() == 2);
    // Only vertices of kept triangles remain, so bounds are those of the good triangle.
    CHECK(m.mesh.positions.size() == 3);
    for (const auto& p : m.mesh.positions) CHECK(p.allFinite());
}

TEST_CASE("materials without 1550 nm data get the documented default and are reported by name", "[gltf]") {
    test::ScratchDir dir;
    GltfBuilder b;
    b.doc["materials"].push_back({{"name", "mystery"}});
    const int p = b.positions(kUnitTriangle);
    b.node({{"mesh", b.mesh(p, -1, 0)}});
    b.node({{"mesh", b.mesh(p, -1)}});  // no material at all
    scene::GltfLoadReport report;
    const scene::Model m = scene::load_gltf(b.write_gltf(dir.path() / "plain.gltf"), &report);
    REQUIRE(m.materials.size() == 2);
    CHECK(m.materials[0].reflectance == scene::kDefaultReflectance);
    CHECK(m.materials[m.mesh.triangle_material[1]].reflectance == scene::kDefaultReflectance);
    CHECK(report.defaulted_materials == std::vector<std::string>{"mystery", "(no material)"});
}

TEST_CASE("malformed glTF is one InputError naming the file and the field", "[gltf]") {
    test::ScratchDir dir;
    auto message = [](const std::filesystem::path& file) -> std::string {
        try {
            scene::load_gltf(file);
        } catch (const InputError& e) {
            return e.what();
        }
        return "no error";
    };
    using Catch::Matchers::Contains;
    CHECK_THAT(message(dir.path() / "absent.glb"), Contains("absent.glb") && Contains("does not exist"));

    std::ofstream(dir.path() / "garbage.gltf") << "{ not json";
    CHECK_THAT(message(dir.path() / "garbage.gltf"), Contains("garbage.gltf"));
    std::ofstream(dir.path() / "garbage.glb") << "glTF but not really";
    CHECK_THAT(message(dir.path() / "garbage.glb"), Contains("garbage.glb"));

    GltfBuilder past_end;
    past_end.node({{"mesh", past_end.mesh(past_end.positions(kUnitTriangle), past_end.indices({0, 1, 7}))}});
    CHECK_THAT(message(past_end.write_gltf(dir.path() / "index.gltf")), Contains("meshes[0].primitives[0].indices"));

    GltfBuilder bad_rho;
    bad_rho.doc["materials"].push_back({{"name", "x"}, {"extras", {{"ladar", {{"reflectance", 1.5}}}}}});
    bad_rho.node({{"mesh", bad_rho.mesh(bad_rho.positions(kUnitTriangle), -1, 0)}});
    CHECK_THAT(message(bad_rho.write_gltf(dir.path() / "rho.gltf")), Contains("materials[0].extras.ladar.reflectance"));

    GltfBuilder vec2;
    vec2.node({{"mesh", vec2.mesh(vec2.positions(kUnitTriangle), -1)}});
    vec2.doc["accessors"][0]["type"] = "VEC2";
    CHECK_THAT(message(vec2.write_gltf(dir.path() / "vec2.gltf")), Contains("POSITION") && Contains("VEC3"));

    GltfBuilder external;
    external.node({{"mesh", external.mesh(external.positions(kUnitTriangle), -1)}});
    json doc = external.finished();
    doc["buffers"][0]["uri"] = "missing.bin";
    std::ofstream(dir.path() / "external.gltf") << doc.dump();
    CHECK_THAT(message(dir.path() / "external.gltf"), Contains("external.gltf"));

    GltfBuilder empty;
    empty.node({{"name", "nothing here"}});
    CHECK_THAT(message(empty.write_gltf(dir.path() / "empty.gltf")), Contains("no usable triangles"));
}

TEST_CASE("a real third-party quadcopter loads whole", "[gltf]") {
    const std::filesystem::path file = test::shared_data("models/drone_nologo.glb");
    if (!std::filesystem::exists(file)) LADARSIM_SKIP("shared model not present: " << file);
    scene::GltfLoadReport report;
    const scene::Model m = scene::load_gltf(file, &report);
    // Its README: 5,170 triangles, extent 65.5 x 82.4 x 36.8 mesh units; its one node scales by 0.01.
    CHECK(report.triangles_loaded + report.degenerate_dropped + report.nonfinite_dropped == 5170);
    CHECK(report.triangles_loaded > 5000);
    const Eigen::Vector3f size = m.bounds().sizes();
    std::vector<float> sorted = {size.x(), size.y(), size.z()};
    std::sort(sorted.begin(), sorted.end());
    CHECK(sorted[0] == Approx(0.368).epsilon(0.01));
    CHECK(sorted[1] == Approx(0.655).epsilon(0.01));
    CHECK(sorted[2] == Approx(0.824).epsilon(0.01));
}
