#include "ladarsim/scene/animation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ladarsim/scene/mesh.h"

namespace ladarsim::scene {
namespace {

struct NodeState {
    Eigen::Vector3d translation;
    Eigen::Quaterniond rotation;
    Eigen::Vector3d scale;
};

int components(AnimationPath path) { return path == AnimationPath::rotation ? 4 : 3; }

// The key's value (not a tangent) of a sampler with `n` numbers a value.
const double* key_value(const AnimationChannel& c, std::size_t k, int n) {
    const std::size_t index = c.interpolation == AnimationInterpolation::cubic_spline ? 3 * k + 1 : k;
    return c.values.data() + index * static_cast<std::size_t>(n);
}

Eigen::Quaterniond quaternion(const double* xyzw) { return Eigen::Quaterniond(xyzw[3], xyzw[0], xyzw[1], xyzw[2]); }

// glTF's sampler at time u (seconds into the clip), into `out` (3 or 4 numbers).
void sample(const AnimationChannel& c, double u, double* out) {
    const int n = components(c.path);
    const std::size_t keys = c.times_s.size();
    const auto copy = [&](const double* v) { std::copy(v, v + n, out); };
    if (keys == 1 || u <= c.times_s.front()) return copy(key_value(c, 0, n));
    if (u >= c.times_s.back()) return copy(key_value(c, keys - 1, n));
    const std::size_t k = static_cast<std::size_t>(std::upper_bound(c.times_s.begin(), c.times_s.end(), u) - c.times_s.begin()) - 1;
    const double dt = c.times_s[k + 1] - c.times_s[k];
    const double s = (u - c.times_s[k]) / dt;
    const double* a = key_value(c, k, n);
    const double* b = key_value(c, k + 1, n);
    switch (c.interpolation) {
        case AnimationInterpolation::step: return copy(a);
        case AnimationInterpolation::linear:
            if (c.path == AnimationPath::rotation) {
                // Eigen's slerp takes the shorter arc, as glTF asks.
                const Eigen::Quaterniond q = quaternion(a).normalized().slerp(s, quaternion(b).normalized());
                out[0] = q.x(), out[1] = q.y(), out[2] = q.z(), out[3] = q.w();
                return;
            }
            for (int i = 0; i < n; ++i) out[i] = a[i] + s * (b[i] - a[i]);
            return;
        case AnimationInterpolation::cubic_spline: {
            // Hermite: the out-tangent of key k and the in-tangent of key k + 1, scaled by dt.
            const double* out_tangent = a + n;
            const double* in_tangent = b - n;
            const double s2 = s * s, s3 = s2 * s;
            const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
            for (int i = 0; i < n; ++i) out[i] = h00 * a[i] + h10 * dt * out_tangent[i] + h01 * b[i] + h11 * dt * in_tangent[i];
            if (c.path == AnimationPath::rotation) {
                const double norm = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2] + out[3] * out[3]);
                if (norm > 0.0)
                    for (int i = 0; i < 4; ++i) out[i] /= norm;
            }
            return;
        }
    }
}

// A channel's value `v` (from sample) set on a node's state.
void apply(AnimationPath path, const double* v, NodeState& s) {
    switch (path) {
        case AnimationPath::translation: s.translation = {v[0], v[1], v[2]}; break;
        case AnimationPath::rotation: s.rotation = quaternion(v).normalized(); break;
        case AnimationPath::scale: s.scale = {v[0], v[1], v[2]}; break;
    }
}

// A node's transform from its parent's frame.
Eigen::Affine3d local_transform(const AnimationNode& node, const NodeState& s) {
    Eigen::Affine3d local;
    if (node.has_matrix) local.matrix() = node.matrix;
    else local = Eigen::Translation3d(s.translation) * s.rotation * Eigen::Scaling(s.scale);
    return local;
}

// Clip time: loops from the scenario's time 0 (and backwards before it).
double clip_time(const AnimationClip& clip, double time_s) {
    if (!(clip.duration_s > 0.0)) return 0.0;
    const double u = std::fmod(time_s, clip.duration_s);
    return u < 0.0 ? u + clip.duration_s : u;
}

// Poses an animation's nodes; its buffers are reused from pose to pose.
class Poser {
public:
    // Every node's model_from_node with the chosen clips at `time_s` (or at rest when `playing` is false).
    const std::vector<Eigen::Affine3d>& pose(const Animation& animation, const AnimationChoice& choice, double time_s, bool playing) {
        animation_ = &animation;
        const auto& nodes = animation.nodes;
        state_.resize(nodes.size());
        for (std::size_t i = 0; i < nodes.size(); ++i) state_[i] = {nodes[i].translation, nodes[i].rotation, nodes[i].scale};
        if (playing) {
            for (std::size_t c = 0; c < animation.clips.size(); ++c) {
                if (!choice.plays(static_cast<std::uint32_t>(c))) continue;
                const AnimationClip& clip = animation.clips[c];
                const double u = clip_time(clip, time_s);
                for (const AnimationChannel& channel : clip.channels) {
                    double v[4];
                    sample(channel, u, v);
                    apply(channel.path, v, state_[channel.node]);
                }
            }
        }
        model_from_node_.assign(nodes.size(), Eigen::Affine3d::Identity());
        done_.assign(nodes.size(), false);
        for (std::size_t i = 0; i < nodes.size(); ++i) resolve(i);
        return model_from_node_;
    }

private:
    // Parents come before children only by chance in glTF: resolve up the chain (the loader has
    // refused cycles).
    void resolve(std::size_t i) {
        if (done_[i]) return;
        const AnimationNode& node = animation_->nodes[i];
        const Eigen::Affine3d local = local_transform(node, state_[i]);
        if (node.parent >= 0) {
            resolve(static_cast<std::size_t>(node.parent));
            model_from_node_[i] = model_from_node_[static_cast<std::size_t>(node.parent)] * local;
        } else {
            model_from_node_[i] = local;
        }
        done_[i] = true;
    }

    const Animation* animation_ = nullptr;
    std::vector<NodeState> state_;
    std::vector<Eigen::Affine3d> model_from_node_;
    std::vector<bool> done_;
};

// Clips the choice plays that have a channel.
bool plays_any(const Animation& animation, const AnimationChoice& choice) {
    for (std::size_t c = 0; c < animation.clips.size(); ++c)
        if (choice.plays(static_cast<std::uint32_t>(c)) && !animation.clips[c].channels.empty()) return true;
    return false;
}

}  // namespace

std::vector<Eigen::Affine3d> rest_model_from_node(const Animation& animation) {
    return Poser().pose(animation, AnimationChoice{}, 0.0, false);
}

std::vector<std::vector<std::uint32_t>> triangles_by_part(const Model& model) {
    const std::size_t parts = model.animation ? model.animation->parts.size() : 0;
    std::vector<std::vector<std::uint32_t>> lists(parts + 1);
    std::vector<bool> in_part(model.mesh.triangles.size(), false);
    for (std::size_t p = 0; p < parts; ++p) {
        const AnimationPart& part = model.animation->parts[p];
        for (std::uint32_t t = part.first_triangle; t < part.first_triangle + part.triangle_count; ++t) {
            lists[p + 1].push_back(t);
            in_part[t] = true;
        }
    }
    for (std::uint32_t t = 0; t < in_part.size(); ++t)
        if (!in_part[t]) lists[0].push_back(t);
    return lists;
}

bool animates(const Model& model, const AnimationChoice& choice) {
    return model.animation && !model.animation->parts.empty() && plays_any(*model.animation, choice);
}

PartMotions::PartMotions(const Model& model, const AnimationChoice& choice) : animation_(model.animation.get()), choice_(choice) {
    if (!animation_) return;
    const std::vector<Eigen::Affine3d> rest = rest_model_from_node(*animation_);
    for (const AnimationPart& part : animation_->parts) {
        rest_from_model_.push_back(rest[part.node].inverse());
        // The part's node and those above it, root first, each with the chosen channels on it in
        // the order the Poser applies them (a later one on the same path wins).
        std::vector<Link>& chain = chains_.emplace_back();
        for (int n = static_cast<int>(part.node); n >= 0; n = animation_->nodes[static_cast<std::size_t>(n)].parent)
            chain.insert(chain.begin(), Link{static_cast<std::uint32_t>(n), {}});
        for (Link& link : chain)
            for (std::size_t c = 0; c < animation_->clips.size(); ++c) {
                if (!choice.plays(static_cast<std::uint32_t>(c))) continue;
                for (const AnimationChannel& channel : animation_->clips[c].channels)
                    if (channel.node == link.node) link.channels.emplace_back(&animation_->clips[c], &channel);
            }
    }
}

Eigen::Affine3d PartMotions::at(std::size_t part, double time_s) const {
    Eigen::Affine3d model_from_node;
    bool root = true;
    for (const Link& link : chains_[part]) {
        const AnimationNode& node = animation_->nodes[link.node];
        NodeState s{node.translation, node.rotation, node.scale};
        for (const auto& [clip, channel] : link.channels) {
            double v[4];
            sample(*channel, clip_time(*clip, time_s), v);
            apply(channel->path, v, s);
        }
        const Eigen::Affine3d local = local_transform(node, s);
        model_from_node = root ? local : model_from_node * local;
        root = false;
    }
    return model_from_node * rest_from_model_[part];
}

void PartMotions::at(double time_s, std::vector<Eigen::Affine3d>& out) const {
    out.clear();
    if (!animation_) return;
    thread_local Poser poser;
    const std::vector<Eigen::Affine3d>& now = poser.pose(*animation_, choice_, time_s, true);
    for (std::size_t p = 0; p < animation_->parts.size(); ++p) out.push_back(now[animation_->parts[p].node] * rest_from_model_[p]);
}

void part_motions(const Model& model, const AnimationChoice& choice, double time_s, std::vector<Eigen::Affine3d>& out) {
    PartMotions(model, choice).at(time_s, out);
}

Eigen::AlignedBox3d animated_bounds(const Model& model, const AnimationChoice& choice) {
    Eigen::AlignedBox3d box;
    const TriangleMesh& mesh = model.mesh;
    if (!animates(model, choice)) {
        for (const Eigen::Vector3f& p : mesh.positions) box.extend(p.cast<double>());
        return box;
    }
    const Animation& animation = *model.animation;
    // Each part's rest box; triangles in no part stay where they are.
    const std::vector<std::vector<std::uint32_t>> lists = triangles_by_part(model);
    std::vector<Eigen::AlignedBox3d> part_box(animation.parts.size());
    for (std::size_t p = 0; p < animation.parts.size(); ++p) part_box[p] = bounds_of(mesh, lists[p + 1]);
    box = bounds_of(mesh, lists[0]);

    // Samples over the longest chosen loop, at least 16 per key interval of its busiest channel.
    double duration = 0.0;
    std::size_t keys = 1;
    for (std::size_t c = 0; c < animation.clips.size(); ++c) {
        if (!choice.plays(static_cast<std::uint32_t>(c))) continue;
        duration = std::max(duration, animation.clips[c].duration_s);
        for (const AnimationChannel& channel : animation.clips[c].channels) keys = std::max(keys, channel.times_s.size());
    }
    const int samples = static_cast<int>(std::max<std::size_t>(512, 16 * keys));
    const PartMotions motions(model, choice);
    std::vector<Eigen::Affine3d> motion;
    std::vector<Eigen::Vector3d> previous(8 * animation.parts.size());
    // The corners of a part's box move by at most `step` between samples; anything of the part lies
    // within step / 2 of a sampled placement's box (the path between two samples is nearly straight).
    double step = 0.0;
    for (int s = 0; s <= samples; ++s) {
        motions.at(duration * s / samples, motion);
        for (std::size_t p = 0; p < animation.parts.size(); ++p) {
            if (part_box[p].isEmpty()) continue;
            for (int k = 0; k < 8; ++k) {
                const Eigen::Vector3d c = motion[p] * part_box[p].corner(static_cast<Eigen::AlignedBox3d::CornerType>(k));
                box.extend(c);
                Eigen::Vector3d& before = previous[8 * p + static_cast<std::size_t>(k)];
                if (s > 0) step = std::max(step, (c - before).norm());
                before = c;
            }
        }
    }
    const Eigen::Vector3d pad = Eigen::Vector3d::Constant(step);
    return Eigen::AlignedBox3d(box.min() - pad, box.max() + pad);
}

}  // namespace ladarsim::scene
