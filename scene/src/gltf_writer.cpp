#include "ladarsim/scene/gltf_writer.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <system_error>

#include <tiny_gltf.h>

#include "ladarsim/core/input_error.h"
#include "ladarsim/scene/animation.h"

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

// One glTF mesh of the given triangles of `model` (indices into its mesh), one primitive per
// material, its vertices in glTF axes.
int add_mesh(tinygltf::Model& g, const Model& model, const std::vector<std::uint32_t>& triangles) {
    constexpr auto unused = static_cast<std::uint32_t>(-1);
    std::vector<std::uint32_t> new_index(model.mesh.positions.size(), unused);
    for (std::uint32_t t : triangles)
        for (std::uint32_t v : model.mesh.triangles[t]) new_index[v] = 0;
    // Vertices keep their order, so a whole mesh is written exactly as it is held.
    std::vector<float> xyz;
    std::vector<double> lo(3, std::numeric_limits<double>::max()), hi(3, std::numeric_limits<double>::lowest());
    std::uint32_t count = 0;
    for (std::size_t v = 0; v < new_index.size(); ++v) {
        if (new_index[v] == unused) continue;
        new_index[v] = count++;
        const Eigen::Vector3f& p = model.mesh.positions[v];
        const float gltf[3] = {p.y(), p.z(), p.x()};
        for (int k = 0; k < 3; ++k) {
            xyz.push_back(gltf[k]);
            lo[static_cast<std::size_t>(k)] = std::min(lo[static_cast<std::size_t>(k)], double(gltf[k]));
            hi[static_cast<std::size_t>(k)] = std::max(hi[static_cast<std::size_t>(k)], double(gltf[k]));
        }
    }
    // With the min/max glTF requires of POSITION.
    tinygltf::Accessor positions;
    positions.bufferView = append_view(g, xyz.data(), xyz.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
    positions.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    positions.count = count;
    positions.type = TINYGLTF_TYPE_VEC3;
    positions.minValues = lo;
    positions.maxValues = hi;
    g.accessors.push_back(positions);
    const int position_accessor = static_cast<int>(g.accessors.size()) - 1;

    tinygltf::Mesh mesh;
    for (std::size_t m = 0; m < model.materials.size(); ++m) {
        std::vector<std::uint32_t> indices;
        for (std::uint32_t t : triangles)
            if (model.mesh.triangle_material[t] == m)
                for (std::uint32_t v : model.mesh.triangles[t]) indices.push_back(new_index[v]);
        if (indices.empty()) continue;
        tinygltf::Accessor index_accessor;
        index_accessor.bufferView = append_view(g, indices.data(), indices.size() * sizeof(std::uint32_t),
                                                TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
        index_accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
        index_accessor.count = indices.size();
        index_accessor.type = TINYGLTF_TYPE_SCALAR;
        g.accessors.push_back(index_accessor);

        tinygltf::Primitive primitive;
        primitive.attributes["POSITION"] = position_accessor;
        primitive.indices = static_cast<int>(g.accessors.size()) - 1;
        primitive.material = static_cast<int>(m);
        primitive.mode = TINYGLTF_MODE_TRIANGLES;
        mesh.primitives.push_back(primitive);
    }
    g.meshes.push_back(mesh);
    return static_cast<int>(g.meshes.size()) - 1;
}

int add_floats(tinygltf::Model& g, const std::vector<float>& values, int type, bool with_range) {
    tinygltf::Accessor a;
    a.bufferView = append_view(g, values.data(), values.size() * sizeof(float), 0);
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.type = type;
    a.count = values.size() / static_cast<std::size_t>(tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(type)));
    if (with_range) {  // glTF requires them of an animation's key times
        a.minValues = {*std::min_element(values.begin(), values.end())};
        a.maxValues = {*std::max_element(values.begin(), values.end())};
    }
    g.accessors.push_back(a);
    return static_cast<int>(g.accessors.size()) - 1;
}

// Model axes to glTF axes, for vectors: the inverse of the loader's mapping.
std::vector<double> to_gltf_axes(const Eigen::Vector3d& v) { return {v.y(), v.z(), v.x()}; }

// A transform in model axes as a glTF node's matrix (column-major, glTF axes).
std::vector<double> gltf_matrix(const Eigen::Matrix4d& model_axes) {
    Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
    p(0, 2) = p(1, 0) = p(2, 1) = p(3, 3) = 1.0;  // model from glTF, as the loader has it
    const Eigen::Matrix4d m = p.transpose() * model_axes * p;
    std::vector<double> out;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) out.push_back(m(r, c));
    return out;
}

// The node hierarchy with each part's triangles under its node, the rest under a root of their
// own, and every clip.
void add_animated_scene(tinygltf::Model& g, const Model& model) {
    const Animation& animation = *model.animation;
    const std::vector<Eigen::Affine3d> rest = rest_model_from_node(animation);
    const std::vector<std::vector<std::uint32_t>> by_part = triangles_by_part(model);
    std::vector<std::vector<std::uint32_t>> node_triangles(animation.nodes.size());
    for (std::size_t p = 0; p < animation.parts.size(); ++p) {
        std::vector<std::uint32_t>& list = node_triangles[animation.parts[p].node];
        list.insert(list.end(), by_part[p + 1].begin(), by_part[p + 1].end());
    }
    for (std::size_t i = 0; i < animation.nodes.size(); ++i) {
        const AnimationNode& n = animation.nodes[i];
        tinygltf::Node node;
        node.name = n.name;
        if (n.has_matrix) {
            node.matrix = gltf_matrix(n.matrix);
        } else {
            node.translation = to_gltf_axes(n.translation);
            const std::vector<double> axis = to_gltf_axes(n.rotation.vec());
            node.rotation = {axis[0], axis[1], axis[2], n.rotation.w()};
            node.scale = to_gltf_axes(n.scale);
        }
        g.nodes.push_back(node);
    }
    g.scenes.push_back(tinygltf::Scene{});
    for (std::size_t i = 0; i < animation.nodes.size(); ++i) {
        const int parent = animation.nodes[i].parent;
        if (parent >= 0) g.nodes[static_cast<std::size_t>(parent)].children.push_back(static_cast<int>(i));
        else g.scenes[0].nodes.push_back(static_cast<int>(i));
    }
    // A part's triangles hang under its node in a child that undoes the node's rest placement,
    // so that their vertices are written in model coordinates, unrounded.
    for (std::size_t i = 0; i < animation.nodes.size(); ++i) {
        if (node_triangles[i].empty()) continue;
        tinygltf::Node holder;
        holder.name = animation.nodes[i].name + " mesh";
        holder.mesh = add_mesh(g, model, node_triangles[i]);
        holder.matrix = gltf_matrix(rest[i].inverse().matrix());
        g.nodes.push_back(holder);
        g.nodes[i].children.push_back(static_cast<int>(g.nodes.size()) - 1);
    }
    const std::vector<std::uint32_t>& still = by_part[0];
    if (!still.empty()) {
        tinygltf::Node node;
        node.name = model.source;
        node.mesh = add_mesh(g, model, still);
        g.nodes.push_back(node);
        g.scenes[0].nodes.push_back(static_cast<int>(g.nodes.size()) - 1);
    }
    for (const AnimationClip& clip : animation.clips) {
        tinygltf::Animation a;
        a.name = clip.name;
        for (const AnimationChannel& channel : clip.channels) {
            tinygltf::AnimationSampler sampler;
            sampler.input = add_floats(g, std::vector<float>(channel.times_s.begin(), channel.times_s.end()), TINYGLTF_TYPE_SCALAR, true);
            const int n = channel.path == AnimationPath::rotation ? 4 : 3;
            std::vector<float> values;
            for (std::size_t i = 0; i < channel.values.size(); i += static_cast<std::size_t>(n)) {
                for (double v : to_gltf_axes({channel.values[i], channel.values[i + 1], channel.values[i + 2]})) values.push_back(static_cast<float>(v));
                if (n == 4) values.push_back(static_cast<float>(channel.values[i + 3]));
            }
            sampler.output = add_floats(g, values, n == 4 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, false);
            sampler.interpolation = channel.interpolation == AnimationInterpolation::step     ? "STEP"
                                    : channel.interpolation == AnimationInterpolation::linear ? "LINEAR"
                                                                                              : "CUBICSPLINE";
            a.samplers.push_back(sampler);
            tinygltf::AnimationChannel target;
            target.sampler = static_cast<int>(a.samplers.size()) - 1;
            target.target_node = static_cast<int>(channel.node);
            target.target_path = channel.path == AnimationPath::translation ? "translation"
                                 : channel.path == AnimationPath::rotation  ? "rotation"
                                                                            : "scale";
            a.channels.push_back(target);
        }
        g.animations.push_back(a);
    }
}

}  // namespace

void write_gltf(const Model& model, const std::filesystem::path& file) {
    const bool binary = file.extension() == ".glb";
    tinygltf::Model g;
    g.asset.version = "2.0";
    g.asset.generator = "ladarsim";
    g.buffers.resize(1);

    for (const Material& m : model.materials) {
        tinygltf::Material material;
        material.name = m.name;
        tinygltf::Value::Object ladar{{"reflectance", tinygltf::Value(m.reflectance)}};
        if (m.is_volume()) {
            ladar["extinction_per_m"] = tinygltf::Value(m.extinction_per_m);
            ladar["backscatter_per_m_sr"] = tinygltf::Value(m.backscatter_per_m_sr);
        }
        material.extras = tinygltf::Value(tinygltf::Value::Object{{"ladar", tinygltf::Value(ladar)}});
        g.materials.push_back(material);
    }
    if (model.animation) {
        add_animated_scene(g, model);
    } else {
        std::vector<std::uint32_t> all(model.mesh.triangles.size());
        for (std::uint32_t t = 0; t < all.size(); ++t) all[t] = t;
        tinygltf::Node node;
        node.mesh = add_mesh(g, model, all);
        node.name = model.source;
        g.nodes.push_back(node);
        g.scenes.push_back(tinygltf::Scene{});
        g.scenes[0].nodes = {0};
    }
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
