#include "ladarsim/scene/gltf_loader.h"

#include <cmath>
#include <algorithm>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <spdlog/spdlog.h>
#include <tiny_gltf.h>

#include "ladarsim/core/input_error.h"
#include "ladarsim/scene/animation.h"

namespace ladarsim::scene {
namespace {

using Matrix4 = Eigen::Matrix4d;

class GltfReader {
public:
    GltfReader(const std::filesystem::path& file, const tinygltf::Model& gltf, GltfLoadReport& report)
        : file_(file.string()), gltf_(gltf), report_(report) {}

    Model read() {
        Model model;
        model.source = file_;
        read_materials(model);
        for (int root : root_nodes()) add_node(root, model_from_gltf(), model, 0);
        if (!gltf_.animations.empty()) read_animation(model);
        drop_unreferenced_vertices(model.mesh);
        report_.triangles_loaded = model.mesh.triangles.size();
        return model;
    }

private:
    [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
        throw InputError(file_, field, problem);
    }

    // glTF is y up with the front along +z; ladarsim models are z up with the front along +x.
    static Matrix4 model_from_gltf() {
        Matrix4 m = Matrix4::Zero();
        m(0, 2) = 1.0;  // model x = glTF z
        m(1, 0) = 1.0;  // model y = glTF x
        m(2, 1) = 1.0;  // model z = glTF y
        m(3, 3) = 1.0;
        return m;
    }

    // Vertices of dropped triangles would otherwise widen Model::bounds() and the BVH.
    static void drop_unreferenced_vertices(TriangleMesh& mesh) {
        constexpr auto unused = static_cast<std::uint32_t>(-1);
        std::vector<std::uint32_t> new_index(mesh.positions.size(), unused);
        std::vector<Eigen::Vector3f> kept;
        for (auto& triangle : mesh.triangles)
            for (std::uint32_t& v : triangle) {
                if (new_index[v] == unused) {
                    new_index[v] = static_cast<std::uint32_t>(kept.size());
                    kept.push_back(mesh.positions[v]);
                }
                v = new_index[v];
            }
        mesh.positions = std::move(kept);
    }

    // glTF material i is Model material i; primitives without one share a default appended on demand.
    std::uint32_t default_material(Model& model) {
        if (!default_material_) {
            default_material_ = static_cast<std::uint32_t>(model.materials.size());
            model.materials.push_back(Material{"(no material)", kDefaultReflectance});
            report_.defaulted_materials.push_back("(no material)");
        }
        return *default_material_;
    }

    void read_materials(Model& model) {
        for (std::size_t i = 0; i < gltf_.materials.size(); ++i) {
            const tinygltf::Material& m = gltf_.materials[i];
            const std::string field = "materials[" + std::to_string(i) + "]";
            Material material{m.name.empty() ? field : m.name, kDefaultReflectance};
            const tinygltf::Value& ladar = m.extras.Get("ladar");
            if (ladar.IsObject() && ladar.Has("reflectance")) {
                const tinygltf::Value& r = ladar.Get("reflectance");
                if (!r.IsNumber()) fail(field + ".extras.ladar.reflectance", "must be a number");
                material.reflectance = r.GetNumberAsDouble();
                if (!(material.reflectance >= 0.0 && material.reflectance <= 1.0))
                    fail(field + ".extras.ladar.reflectance", "must lie in [0, 1], got " + std::to_string(material.reflectance));
            } else if (!(ladar.IsObject() && ladar.Has("extinction_per_m"))) {
                report_.defaulted_materials.push_back(material.name);
            }
            if (ladar.IsObject()) {
                material.extinction_per_m = non_negative(ladar, "extinction_per_m", field);
                material.backscatter_per_m_sr = non_negative(ladar, "backscatter_per_m_sr", field);
            }
            model.materials.push_back(std::move(material));
        }
    }

    double non_negative(const tinygltf::Value& ladar, const char* key, const std::string& field) const {
        if (!ladar.Has(key)) return 0.0;
        const tinygltf::Value& v = ladar.Get(key);
        if (!v.IsNumber() || !(v.GetNumberAsDouble() >= 0.0) || !std::isfinite(v.GetNumberAsDouble()))
            fail(field + ".extras.ladar." + key, "must be a finite number >= 0");
        return v.GetNumberAsDouble();
    }

    std::vector<int> root_nodes() const {
        if (!gltf_.scenes.empty()) {
            const int s = gltf_.defaultScene >= 0 ? gltf_.defaultScene : 0;
            if (s >= static_cast<int>(gltf_.scenes.size())) fail("scene", "index " + std::to_string(s) + " out of range");
            return gltf_.scenes[static_cast<std::size_t>(s)].nodes;
        }
        // No scene: every node that is nobody's child is a root.
        std::vector<bool> is_child(gltf_.nodes.size(), false);
        for (const auto& node : gltf_.nodes)
            for (int c : node.children)
                if (c >= 0 && c < static_cast<int>(is_child.size())) is_child[static_cast<std::size_t>(c)] = true;
        std::vector<int> roots;
        for (std::size_t i = 0; i < is_child.size(); ++i)
            if (!is_child[i]) roots.push_back(static_cast<int>(i));
        return roots;
    }

    Matrix4 local_transform(const tinygltf::Node& node, const std::string& field) const {
        if (node.matrix.size() == 16) {
            Matrix4 m;
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) m(r, c) = node.matrix[static_cast<std::size_t>(4 * c + r)];  // column-major
            return m;
        }
        if (!node.matrix.empty()) fail(field + ".matrix", "must have 16 numbers");
        Eigen::Affine3d t = Eigen::Affine3d::Identity();
        if (node.translation.size() == 3) t.translate(Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]));
        if (node.rotation.size() == 4) {
            // glTF stores (x, y, z, w); Eigen's constructor takes (w, x, y, z).
            Eigen::Quaterniond q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
            if (!(q.norm() > 0.0)) fail(field + ".rotation", "is not a rotation quaternion");
            t.rotate(q.normalized());
        }
        if (node.scale.size() == 3) t.scale(Eigen::Vector3d(node.scale[0], node.scale[1], node.scale[2]));
        return t.matrix();
    }

    void add_node(int index, const Matrix4& parent, Model& model, int depth) {
        const std::string field = "nodes[" + std::to_string(index) + "]";
        if (index < 0 || index >= static_cast<int>(gltf_.nodes.size())) fail(field, "index out of range");
        // A cycle in children would recurse forever; glTF forbids them but files can still contain one.
        if (depth > static_cast<int>(gltf_.nodes.size())) fail(field + ".children", "node hierarchy contains a cycle");
        const tinygltf::Node& node = gltf_.nodes[static_cast<std::size_t>(index)];
        const Matrix4 world = parent * local_transform(node, field);
        if (node.mesh >= 0) {
            add_mesh(node.mesh, world, model);
            triangle_node_.resize(model.mesh.triangles.size(), index);
        }
        for (int child : node.children) add_node(child, world, model, depth + 1);
    }

    void add_mesh(int index, const Matrix4& transform, Model& model) {
        const std::string field = "meshes[" + std::to_string(index) + "]";
        if (index >= static_cast<int>(gltf_.meshes.size())) fail(field, "index out of range");
        const auto& primitives = gltf_.meshes[static_cast<std::size_t>(index)].primitives;
        for (std::size_t p = 0; p < primitives.size(); ++p)
            add_primitive(primitives[p], field + ".primitives[" + std::to_string(p) + "]", transform, model);
    }

    void add_primitive(const tinygltf::Primitive& primitive, const std::string& field, const Matrix4& transform, Model& model) {
        // Points and lines have no surface to reflect a beam; strips and fans are rare enough in
        // exported models that we decode only plain triangle lists and say so.
        if (primitive.mode != TINYGLTF_MODE_TRIANGLES) {
            if (primitive.mode == TINYGLTF_MODE_TRIANGLE_STRIP || primitive.mode == TINYGLTF_MODE_TRIANGLE_FAN)
                spdlog::warn("{}: {}: triangle strips and fans are not supported; primitive skipped", file_, field);
            return;
        }
        const auto position = primitive.attributes.find("POSITION");
        if (position == primitive.attributes.end()) fail(field + ".attributes", "has no POSITION");
        const std::vector<Eigen::Vector3d> vertices = read_floats3(position->second, field + ".attributes.POSITION");
        std::vector<std::uint32_t> indices;
        if (primitive.indices >= 0) {
            indices = read_indices(primitive.indices, field + ".indices");
        } else {
            indices.resize(vertices.size());
            for (std::size_t i = 0; i < indices.size(); ++i) indices[i] = static_cast<std::uint32_t>(i);
        }
        if (indices.size() % 3 != 0) fail(field, "triangle list length " + std::to_string(indices.size()) + " is not a multiple of 3");
        if (primitive.material >= static_cast<int>(gltf_.materials.size())) fail(field + ".material", "index out of range");
        const std::uint32_t material =
            primitive.material >= 0 ? static_cast<std::uint32_t>(primitive.material) : default_material(model);

        // Transform every vertex once; non-finite ones are marked so their triangles can be dropped.
        const auto base = static_cast<std::uint32_t>(model.mesh.positions.size());
        std::vector<bool> finite(vertices.size());
        for (std::size_t i = 0; i < vertices.size(); ++i) {
            const Eigen::Vector3d p = (transform * vertices[i].homogeneous()).head<3>();
            finite[i] = p.allFinite() && p.cast<float>().allFinite();
            model.mesh.positions.push_back(finite[i] ? Eigen::Vector3f(p.cast<float>()) : Eigen::Vector3f::Zero());
        }
        for (std::size_t t = 0; t < indices.size(); t += 3) {
            const std::uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
            if (a >= vertices.size() || b >= vertices.size() || c >= vertices.size())
                fail(field + ".indices", "index exceeds the vertex count " + std::to_string(vertices.size()));
            if (!finite[a] || !finite[b] || !finite[c]) {
                ++report_.nonfinite_dropped;
                continue;
            }
            const Eigen::Vector3f& pa = model.mesh.positions[base + a];
            const Eigen::Vector3f area2 = (model.mesh.positions[base + b] - pa).cross(model.mesh.positions[base + c] - pa);
            if (a == b || b == c || a == c || !(area2.norm() > 0.0f)) {
                ++report_.degenerate_dropped;
                continue;
            }
            model.mesh.triangles.push_back({base + a, base + b, base + c});
            model.mesh.triangle_material.push_back(material);
        }
    }

    // The bytes of an accessor: pointer to element i's first component and the stride between elements.
    struct AccessorView {
        const unsigned char* data;
        std::size_t stride;
        std::size_t count;
        int component_type;
        int components;
        bool normalized;
    };

    AccessorView view(int index, const std::string& field) const {
        if (index < 0 || index >= static_cast<int>(gltf_.accessors.size())) fail(field, "accessor index out of range");
        const tinygltf::Accessor& a = gltf_.accessors[static_cast<std::size_t>(index)];
        if (a.sparse.isSparse) fail(field, "sparse accessors are not supported");
        if (a.bufferView < 0 || a.bufferView >= static_cast<int>(gltf_.bufferViews.size()))
            fail(field, "accessor has no valid bufferView");
        const tinygltf::BufferView& bv = gltf_.bufferViews[static_cast<std::size_t>(a.bufferView)];
        if (bv.buffer < 0 || bv.buffer >= static_cast<int>(gltf_.buffers.size())) fail(field, "bufferView has no valid buffer");
        const std::vector<unsigned char>& buffer = gltf_.buffers[static_cast<std::size_t>(bv.buffer)].data;
        const int stride = a.ByteStride(bv);
        const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
        const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
        if (stride <= 0 || components <= 0 || size <= 0) fail(field, "accessor has an invalid type or stride");
        const std::size_t begin = bv.byteOffset + a.byteOffset;
        const std::size_t end = a.count == 0 ? begin
                                             : begin + (a.count - 1) * static_cast<std::size_t>(stride) +
                                                   static_cast<std::size_t>(components * size);
        if (end > buffer.size() || end > bv.byteOffset + bv.byteLength) fail(field, "accessor reads past the end of its buffer");
        return {buffer.data() + begin, static_cast<std::size_t>(stride), a.count, a.componentType, components, a.normalized};
    }

    static double component(const unsigned char* p, int type, bool normalized) {
        auto read = [p](auto zero) {
            decltype(zero) v;
            std::memcpy(&v, p, sizeof v);
            return v;
        };
        switch (type) {
            case TINYGLTF_COMPONENT_TYPE_FLOAT: return read(float{});
            case TINYGLTF_COMPONENT_TYPE_BYTE: return normalized ? std::max(read(std::int8_t{}) / 127.0, -1.0) : read(std::int8_t{});
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? read(std::uint8_t{}) / 255.0 : read(std::uint8_t{});
            case TINYGLTF_COMPONENT_TYPE_SHORT: return normalized ? std::max(read(std::int16_t{}) / 32767.0, -1.0) : read(std::int16_t{});
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return normalized ? read(std::uint16_t{}) / 65535.0 : read(std::uint16_t{});
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return read(std::uint32_t{});
            default: return std::nan("");
        }
    }

    std::vector<Eigen::Vector3d> read_floats3(int index, const std::string& field) const {
        const AccessorView v = view(index, field);
        if (v.components != 3) fail(field, "must be a VEC3 accessor");
        if (v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT || v.component_type == TINYGLTF_COMPONENT_TYPE_DOUBLE)
            fail(field, "component type " + std::to_string(v.component_type) + " is not allowed for positions");
        const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(v.component_type));
        std::vector<Eigen::Vector3d> out(v.count);
        for (std::size_t i = 0; i < v.count; ++i)
            for (int c = 0; c < 3; ++c)
                out[i][c] = component(v.data + i * v.stride + static_cast<std::size_t>(c * size), v.component_type, v.normalized);
        return out;
    }

    std::vector<std::uint32_t> read_indices(int index, const std::string& field) const {
        const AccessorView v = view(index, field);
        if (v.components != 1) fail(field, "must be a SCALAR accessor");
        if (v.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && v.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            v.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            fail(field, "indices must be unsigned integers");
        std::vector<std::uint32_t> out(v.count);
        for (std::size_t i = 0; i < v.count; ++i)
            out[i] = static_cast<std::uint32_t>(component(v.data + i * v.stride, v.component_type, false));
        return out;
    }

    // glTF axes to model axes, for vectors (translations, scales, a quaternion's axis part): the
    // transforms of the node hierarchy become model_from_gltf * T * model_from_gltf^-1.
    static Eigen::Vector3d to_model_axes(const double* gltf) { return {gltf[2], gltf[0], gltf[1]}; }

    void read_animation(Model& model) {
        auto animation = std::make_shared<Animation>();
        std::vector<bool> animated(gltf_.nodes.size(), false);
        for (std::size_t a = 0; a < gltf_.animations.size(); ++a) animation->clips.push_back(read_clip(a, animated));
        read_nodes(*animation);
        // Each triangle moves with the deepest animated node above it (its own node included);
        // triangles under none are left out of every part.
        const auto driver = [&](int node) {
            for (; node >= 0; node = animation->nodes[static_cast<std::size_t>(node)].parent)
                if (animated[static_cast<std::size_t>(node)]) return node;
            return -1;
        };
        TriangleMesh& mesh = model.mesh;
        std::vector<std::size_t> order(mesh.triangles.size());
        std::vector<int> drivers(mesh.triangles.size());
        for (std::size_t t = 0; t < order.size(); ++t) {
            order[t] = t;
            drivers[t] = driver(triangle_node_[t]);
        }
        std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return drivers[a] < drivers[b]; });
        TriangleMesh sorted;
        sorted.positions = std::move(mesh.positions);
        for (std::size_t t : order) {
            sorted.triangles.push_back(mesh.triangles[t]);
            sorted.triangle_material.push_back(mesh.triangle_material[t]);
            const int d = drivers[t];
            if (d < 0) continue;
            const auto index = static_cast<std::uint32_t>(sorted.triangles.size() - 1);
            if (animation->parts.empty() || animation->parts.back().node != static_cast<std::uint32_t>(d))
                animation->parts.push_back(AnimationPart{static_cast<std::uint32_t>(d), index, 0});
            ++animation->parts.back().triangle_count;
        }
        mesh = std::move(sorted);
        model.animation = std::move(animation);
    }

    void read_nodes(Animation& animation) const {
        const Matrix4 p = model_from_gltf();
        animation.nodes.resize(gltf_.nodes.size());
        for (std::size_t i = 0; i < gltf_.nodes.size(); ++i) {
            const tinygltf::Node& node = gltf_.nodes[i];
            const std::string field = "nodes[" + std::to_string(i) + "]";
            AnimationNode& n = animation.nodes[i];
            n.name = node.name;
            for (int c : node.children) {
                if (c < 0 || c >= static_cast<int>(gltf_.nodes.size())) fail(field + ".children", "index out of range");
                if (animation.nodes[static_cast<std::size_t>(c)].parent >= 0) fail(field + ".children", "node " + std::to_string(c) + " has two parents");
                animation.nodes[static_cast<std::size_t>(c)].parent = static_cast<int>(i);
            }
            if (!node.matrix.empty()) {
                n.has_matrix = true;
                n.matrix = p * local_transform(node, field) * p.transpose();
                continue;
            }
            if (node.translation.size() == 3) n.translation = to_model_axes(node.translation.data());
            if (node.rotation.size() == 4) {
                const Eigen::Vector3d axis = to_model_axes(node.rotation.data());
                n.rotation = Eigen::Quaterniond(node.rotation[3], axis.x(), axis.y(), axis.z()).normalized();
            }
            if (node.scale.size() == 3) n.scale = to_model_axes(node.scale.data());
        }
        // A cycle would make the poser walk up forever.
        for (std::size_t i = 0; i < animation.nodes.size(); ++i) {
            std::size_t steps = 0;
            for (int n = static_cast<int>(i); n >= 0; n = animation.nodes[static_cast<std::size_t>(n)].parent)
                if (++steps > animation.nodes.size()) fail("nodes[" + std::to_string(i) + "]", "node hierarchy contains a cycle");
        }
    }

    AnimationClip read_clip(std::size_t a, std::vector<bool>& animated) const {
        const tinygltf::Animation& g = gltf_.animations[a];
        const std::string field = "animations[" + std::to_string(a) + "]";
        AnimationClip clip;
        clip.name = g.name.empty() ? field : g.name;
        for (std::size_t c = 0; c < g.channels.size(); ++c) {
            const tinygltf::AnimationChannel& gc = g.channels[c];
            const std::string cfield = field + ".channels[" + std::to_string(c) + "]";
            AnimationChannel channel;
            if (gc.target_path == "weights") {
                spdlog::warn("{}: {}: morph target weights are not supported; channel skipped", file_, cfield);
                continue;
            }
            if (gc.target_path == "translation") channel.path = AnimationPath::translation;
            else if (gc.target_path == "rotation") channel.path = AnimationPath::rotation;
            else if (gc.target_path == "scale") channel.path = AnimationPath::scale;
            else fail(cfield + ".target.path", "unknown path '" + gc.target_path + "'");
            if (gc.target_node < 0 || gc.target_node >= static_cast<int>(gltf_.nodes.size())) fail(cfield + ".target.node", "index out of range");
            if (!gltf_.nodes[static_cast<std::size_t>(gc.target_node)].matrix.empty())
                fail(cfield + ".target.node", "an animated node must not have a matrix");
            channel.node = static_cast<std::uint32_t>(gc.target_node);
            if (gc.sampler < 0 || gc.sampler >= static_cast<int>(g.samplers.size())) fail(cfield + ".sampler", "index out of range");
            const std::string sfield = field + ".samplers[" + std::to_string(gc.sampler) + "]";
            read_sampler(g.samplers[static_cast<std::size_t>(gc.sampler)], sfield, channel);
            clip.duration_s = std::max(clip.duration_s, channel.times_s.back());
            animated[channel.node] = true;
            clip.channels.push_back(std::move(channel));
        }
        return clip;
    }

    void read_sampler(const tinygltf::AnimationSampler& s, const std::string& field, AnimationChannel& channel) const {
        if (s.interpolation.empty() || s.interpolation == "LINEAR") channel.interpolation = AnimationInterpolation::linear;
        else if (s.interpolation == "STEP") channel.interpolation = AnimationInterpolation::step;
        else if (s.interpolation == "CUBICSPLINE") channel.interpolation = AnimationInterpolation::cubic_spline;
        else fail(field + ".interpolation", "must be LINEAR, STEP or CUBICSPLINE, got '" + s.interpolation + "'");
        const AccessorView in = view(s.input, field + ".input");
        if (in.components != 1 || in.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT) fail(field + ".input", "must be a SCALAR float accessor");
        if (in.count == 0) fail(field + ".input", "has no keys");
        for (std::size_t i = 0; i < in.count; ++i) {
            const double t = component(in.data + i * in.stride, in.component_type, false);
            if (!std::isfinite(t) || t < 0.0 || (!channel.times_s.empty() && !(t > channel.times_s.back())))
                fail(field + ".input", "key times must be finite, >= 0 and increasing");
            channel.times_s.push_back(t);
        }
        const int n = channel.path == AnimationPath::rotation ? 4 : 3;
        const AccessorView out = view(s.output, field + ".output");
        if (out.components != n) fail(field + ".output", n == 4 ? "must be a VEC4 accessor for rotation" : "must be a VEC3 accessor");
        const std::size_t per_key = channel.interpolation == AnimationInterpolation::cubic_spline ? 3 : 1;
        if (out.count != per_key * in.count)
            fail(field + ".output", "has " + std::to_string(out.count) + " values for " + std::to_string(in.count) + " keys");
        const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(out.component_type));
        for (std::size_t i = 0; i < out.count; ++i) {
            double v[4];
            for (int c = 0; c < n; ++c) v[c] = component(out.data + i * out.stride + static_cast<std::size_t>(c * size), out.component_type, out.normalized);
            for (int c = 0; c < n; ++c)
                if (!std::isfinite(v[c])) fail(field + ".output", "value " + std::to_string(i) + " is not finite");
            const Eigen::Vector3d axes = to_model_axes(v);
            channel.values.insert(channel.values.end(), {axes.x(), axes.y(), axes.z()});
            if (n == 4) channel.values.push_back(v[3]);
        }
    }

    std::string file_;
    const tinygltf::Model& gltf_;
    GltfLoadReport& report_;
    std::optional<std::uint32_t> default_material_;
    std::vector<int> triangle_node_;  // the glTF node each triangle came from
};

}  // namespace

Model load_gltf(const std::filesystem::path& file, GltfLoadReport* report) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) throw InputError(file.string(), "file", "does not exist or is not a regular file");
    tinygltf::TinyGLTF loader;
    tinygltf::Model gltf;
    std::string error, warning;
    const bool binary = file.extension() == ".glb" || file.extension() == ".GLB";
    const bool ok = binary ? loader.LoadBinaryFromFile(&gltf, &error, &warning, file.string())
                           : loader.LoadASCIIFromFile(&gltf, &error, &warning, file.string());
    if (!ok) {
        std::string first_line = error.substr(0, error.find('\n'));
        if (first_line.empty()) first_line = "tinygltf could not parse it";
        throw InputError(file.string(), binary ? "glb" : "gltf", first_line);
    }
    GltfLoadReport local;
    GltfLoadReport& r = report ? *report : local;
    r = GltfLoadReport{};
    Model model = GltfReader(file, gltf, r).read();
    if (model.mesh.triangles.empty()) throw InputError(file.string(), "meshes", "contains no usable triangles");
    for (const std::string& name : r.defaulted_materials)
        spdlog::warn("{}: material '{}' has no extras.ladar.reflectance; using the default {}", file.string(), name, kDefaultReflectance);
    if (r.degenerate_dropped + r.nonfinite_dropped > 0)
        spdlog::info("{}: dropped {} degenerate and {} non-finite triangles", file.string(), r.degenerate_dropped, r.nonfinite_dropped);
    return model;
}

}  // namespace ladarsim::scene
