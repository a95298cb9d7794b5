#include "ladarsim/scene/gltf_writer.h"

#include <cstring>
#include <limits>
#include <system_error>

#include <tiny_gltf.h>

#include "ladarsim/core/input_error.h"

namespace ladarsim::scene {
namespace {

int append_view(tinygltf::Model& g, const void* data, std::size_t bytes, int target) {
    auto& buffer = g.buffers[0].data;
    const std::size_t offset = buffer.size();
    buffer.resize(offset + bytes);
    std::memcpy(buffer.data() + offset, data, bytes);
    while (buffer.size() % 4) buffer.push_back(0);  // keep the next view 4-byte aligned
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = offset;
    view.byteLength = bytes;
    view.target = target;
    g.bufferViews.push_back(view);
    return static_cast<int>(g.bufferViews.size()) - 1;
}

}  // namespace

void write_gltf(const Model& model, const std::filesystem::path& file) {
    const bool binary = file.extension() == ".glb";
    tinygltf::Model g;
    g.asset.version = "2.0";
    g.asset.generator = "ladarsim";
    g.buffers.resize(1);

    // One shared vertex array in glTF axes, with the min/max glTF requires of POSITION.
    std::vector<float> xyz;
    xyz.reserve(3 * model.mesh.positions.size());
    std::vector<double> lo(3, std::numeric_limits<double>::max()), hi(3, std::numeric_limits<double>::lowest());
    for (const Eigen::Vector3f& p : model.mesh.positions) {
        const float gltf[3] = {p.y(), p.z(), p.x()};
        for (int k = 0; k < 3; ++k) {
            xyz.push_back(gltf[k]);
            lo[static_cast<std::size_t>(k)] = std::min(lo[static_cast<std::size_t>(k)], double(gltf[k]));
            hi[static_cast<std::size_t>(k)] = std::max(hi[static_cast<std::size_t>(k)], double(gltf[k]));
        }
    }
    tinygltf::Accessor positions;
    positions.bufferView = append_view(g, xyz.data(), xyz.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
    positions.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    positions.count = model.mesh.positions.size();
    positions.type = TINYGLTF_TYPE_VEC3;
    positions.minValues = lo;
    positions.maxValues = hi;
    g.accessors.push_back(positions);

    tinygltf::Mesh mesh;
    for (std::size_t m = 0; m < model.materials.size(); ++m) {
        tinygltf::Material material;
        material.name = model.materials[m].name;
        tinygltf::Value::Object ladar{{"reflectance", tinygltf::Value(model.materials[m].reflectance)}};
        if (model.materials[m].is_volume()) {
            ladar["extinction_per_m"] = tinygltf::Value(model.materials[m].extinction_per_m);
            ladar["backscatter_per_m_sr"] = tinygltf::Value(model.materials[m].backscatter_per_m_sr);
        }
        material.extras = tinygltf::Value(tinygltf::Value::Object{{"ladar", tinygltf::Value(ladar)}});
        g.materials.push_back(material);

        std::vector<std::uint32_t> indices;
        for (std::size_t t = 0; t < model.mesh.triangles.size(); ++t)
            if (model.mesh.triangle_material[t] == m)
                indices.insert(indices.end(), model.mesh.triangles[t].begin(), model.mesh.triangles[t].end());
        if (indices.empty()) continue;
        tinygltf::Accessor index_accessor;
        index_accessor.bufferView = append_view(g, indices.data(), indices.size() * sizeof(std::uint32_t),
                                                TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
        index_accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
        index_accessor.count = indices.size();
        index_accessor.type = TINYGLTF_TYPE_SCALAR;
        g.accessors.push_back(index_accessor);

        tinygltf::Primitive primitive;
        primitive.attributes["POSITION"] = 0;
        primitive.indices = static_cast<int>(g.accessors.size()) - 1;
        primitive.material = static_cast<int>(m);
        primitive.mode = TINYGLTF_MODE_TRIANGLES;
        mesh.primitives.push_back(primitive);
    }
    g.meshes.push_back(mesh);
    tinygltf::Node node;
    node.mesh = 0;
    node.name = model.source;
    g.nodes.push_back(node);
    g.scenes.push_back(tinygltf::Scene{});
    g.scenes[0].nodes = {0};
    g.defaultScene = 0;

    const std::filesystem::path tmp = std::filesystem::path(file.string() + ".tmp");
    tinygltf::TinyGLTF writer;
    // embedImages, embedBuffers, prettyPrint, writeBinary
    if (!writer.WriteGltfSceneToFile(&g, tmp.string(), true, true, !binary, binary)) {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
        throw InputError(file.string(), "write", "tinygltf could not write the file");
    }
    std::error_code ec;
    std::filesystem::rename(tmp, file, ec);
    if (ec) throw InputError(file.string(), "write", ec.message());
}

}  // namespace ladarsim::scene
