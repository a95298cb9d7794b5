// Procedural models: sizes from their specification, closed outward-facing surfaces (by the
// divergence theorem), and a write/load round trip through glTF.
#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <utility>

#include <nlohmann/json.hpp>

#include "ladarsim/scene/gltf_loader.h"
#include "ladarsim/scene/gltf_writer.h"
#include "ladarsim/scene/procedural_models.h"
#include "../support/scratch_dir.h"

using namespace ladarsim;
using namespace ladarsim::scene;

namespace {

/// Every undirected edge is shared by exactly two triangles, used once in each direction.
bool closed_and_consistent(const Model& m) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (const auto& t : m.mesh.triangles)
        for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
    for (const auto& [edge, count] : directed) {
        if (count != 1) return false;
        const auto reverse = directed.find({edge.second, edge.first});
        if (reverse == directed.end() || reverse->second != 1) return false;
    }
    return true;
}

/// Enclosed volume by the divergence theorem: positive only when triangles face outwards.
double signed_volume(const Model& m) {
    double v = 0.0;
    for (const auto& t : m.mesh.triangles) {
        const Eigen::Vector3d a = m.mesh.positions[t[0]].cast<double>(), b = m.mesh.positions[t[1]].cast<double>(),
                              c = m.mesh.positions[t[2]].cast<double>();
        v += a.dot(b.cross(c)) / 6.0;
    }
    return v;
}

}  // namespace

TEST_CASE("the quadcopter spans 0.30 m rotor tip to rotor tip and is closed", "[procedural]") {
    const Model q = make_quadcopter();
    const Eigen::AlignedBox3f box = q.bounds();
    CHECK(box.sizes().x() == Approx(0.30).margin(1e-3));
    CHECK(box.sizes().y() == Approx(0.30).margin(1e-3));
    CHECK(box.center().head<2>().norm() < 1e-3f);
    CHECK(closed_and_consistent(q));
    // Overlapping closed pieces: the sum of their volumes is positive and at least the body's.
    CHECK(signed_volume(q) > 0.10 * 0.10 * 0.05);
}

TEST_CASE("a box building encloses length x width x height, facing outwards", "[procedural]") {
    const Model b = make_box_building(20.0, 12.0, 15.0);
    CHECK(closed_and_consistent(b));
    CHECK(signed_volume(b) == Approx(20.0 * 12.0 * 15.0).epsilon(1e-6));
    CHECK(b.bounds().min().z() == 0.0f);
}

TEST_CASE("a tree is a closed trunk and crown of the given height", "[procedural]") {
    const Model t = make_tree(8.0);
    CHECK(closed_and_consistent(t));
    CHECK(signed_volume(t) > 0.0);
    CHECK(t.bounds().max().z() == Approx(8.0f));
}

TEST_CASE("the terrain covers its stated area, stays low near the sensor and rises to the ridge", "[procedural]") {
    const Model t = make_terrain();
    const Eigen::AlignedBox3f box = t.bounds();
    CHECK(box.min().x() == -100.0f);
    CHECK(box.max().x() == 3000.0f);
    CHECK(box.min().y() == -600.0f);
    CHECK(box.max().y() == 600.0f);
    CHECK(box.max().z() > 80.0f);
    CHECK(box.max().z() < 152.0f);
    float near_max = -1e9f;
    for (const auto& p : t.mesh.positions)
        if (p.x() < 700.0f) near_max = std::max(near_max, p.z());
    CHECK(near_max < 2.0f);
    // Upward normals everywhere: a heightfield seen from above.
    for (const auto& tri : t.mesh.triangles) {
        const Eigen::Vector3f n = (t.mesh.positions[tri[1]] - t.mesh.positions[tri[0]])
                                      .cross(t.mesh.positions[tri[2]] - t.mesh.positions[tri[0]]);
        REQUIRE(n.z() > 0.0f);
    }
}

TEST_CASE("write_gltf and load_gltf give the model back, as .glb and as .gltf", "[procedural][gltf]") {
    test::ScratchDir dir;
    const Model q = make_quadcopter();
    for (const char* name : {"q.glb", "q.gltf"}) {
        write_gltf(q, dir / name);
        GltfLoadReport report;
        const Model back = load_gltf(dir / name, &report);
        CHECK(report.defaulted_materials.empty());
        REQUIRE(back.mesh.triangles.size() == q.mesh.triangles.size());
        REQUIRE(back.materials.size() == q.materials.size());
        for (std::size_t m = 0; m < q.materials.size(); ++m) {
            CHECK(back.materials[m].name == q.materials[m].name);
            CHECK(back.materials[m].reflectance == q.materials[m].reflectance);
        }
        // Triangles come back grouped by material; compare them as sets of corner positions.
        std::multiset<std::array<float, 10>> a, b;
        auto key = [](const Model& m, std::size_t t) {
            std::array<float, 10> k{};
            for (int c = 0; c < 3; ++c)
                for (int d = 0; d < 3; ++d) k[static_cast<std::size_t>(3 * c + d)] = m.mesh.positions[m.mesh.triangles[t][c]][d];
            k[9] = static_cast<float>(m.mesh.triangle_material[t]);
            return k;
        };
        for (std::size_t t = 0; t < q.mesh.triangles.size(); ++t) {
            a.insert(key(q, t));
            b.insert(key(back, t));
        }
        CHECK(a == b);
    }
    write_default_assets(dir / "assets");
    for (const char* name : {"quadcopter.glb", "terrain.glb", "building.glb", "tree.glb"})
        CHECK(std::filesystem::file_size(dir / "assets" / name) > 0);
}

TEST_CASE("write_gltf writes a .glb with the glTF magic and a .gltf that is glTF 2.0 JSON", "[procedural][gltf]") {
    // Checked with readers other than load_gltf, so a writer and loader sharing a mistake cannot hide it.
    test::ScratchDir dir;
    const Model building = make_box_building(20.0, 12.0, 15.0);
    write_gltf(building, dir / "b.glb");
    write_gltf(building, dir / "b.gltf");
    CHECK_FALSE(std::filesystem::exists(dir / "b.glb.tmp"));
    CHECK_FALSE(std::filesystem::exists(dir / "b.gltf.tmp"));

    std::ifstream glb(dir / "b.glb", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(glb)), std::istreambuf_iterator<char>());
    REQUIRE(bytes.size() > 12);
    CHECK(bytes.substr(0, 4) == "glTF");

    std::ifstream text(dir / "b.gltf");
    const nlohmann::json j = nlohmann::json::parse(text);  // throws if it is not JSON
    CHECK(j.at("asset").at("version") == "2.0");
    REQUIRE(j.at("materials").size() == 1);
    CHECK(j["materials"][0]["name"] == "concrete");
    CHECK(j["materials"][0]["extras"]["ladar"]["reflectance"].get<double>() == 0.35);
}

TEST_CASE("birds, aircraft and clouds have their specified sizes, and clouds are volumes", "[procedural]") {
    const Model bird = make_bird(0.4);
    CHECK(bird.bounds().sizes().y() == Approx(0.4).epsilon(0.01));
    CHECK(closed_and_consistent(bird));
    const Model light = make_light_aircraft();
    CHECK(light.bounds().sizes().x() == Approx(7.2).epsilon(0.01));
    CHECK(light.bounds().sizes().y() == Approx(11.0).epsilon(0.01));
    const Model airliner = make_airliner();
    CHECK(airliner.bounds().sizes().x() == Approx(37.6).epsilon(0.01));
    CHECK(airliner.bounds().sizes().y() == Approx(34.0).epsilon(0.01));
    const Model cloud = make_cloud(60.0, 0.03);
    CHECK(cloud.is_volume());
    CHECK(closed_and_consistent(cloud));
    CHECK(cloud.bounds().sizes().x() == Approx(60.0).epsilon(0.01));
    CHECK(cloud.materials[0].backscatter_per_m_sr == Approx(0.03 / 20.0));
    CHECK(signed_volume(cloud) > 0.0);
    CHECK_FALSE(make_quadcopter().is_volume());
}
