#pragma once
// glTF node animation (translation, rotation and scale channels) of a loaded model: which parts of
// the mesh each animated node carries, and where they are at any time.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ladarsim::scene {

struct Model;

/// A node of the model's hierarchy in model axes (x forward, y left, z up: glTF's node transforms
/// are turned into these axes on loading). Its local transform at rest is translation * rotation *
/// scale; an animation channel replaces one of the three while it plays.
struct AnimationNode {
    std::string name;
    int parent = -1;  ///< index into Animation::nodes, -1 for a root
    /// A node given as a matrix (never animated: glTF forbids it) keeps it here; else the TRS below.
    bool has_matrix = false;
    Eigen::Matrix4d matrix = Eigen::Matrix4d::Identity();
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();
    Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
    Eigen::Vector3d scale = Eigen::Vector3d::Ones();
};

enum class AnimationPath : std::uint8_t { translation, rotation, scale };
enum class AnimationInterpolation : std::uint8_t { step, linear, cubic_spline };

/// One glTF channel with its sampler: key times (increasing) and values in model axes, 3 numbers a
/// key for translation and scale, 4 (x y z w, unit) for rotation. A cubic spline has three values a
/// key: in-tangent, value, out-tangent (glTF's order).
struct AnimationChannel {
    std::uint32_t node = 0;
    AnimationPath path = AnimationPath::rotation;
    AnimationInterpolation interpolation = AnimationInterpolation::linear;
    std::vector<double> times_s;
    std::vector<double> values;
};

/// A glTF animation: its channels play together and loop with the period duration_s (the latest
/// key time of any of its channels).
struct AnimationClip {
    std::string name;
    std::vector<AnimationChannel> channels;
    double duration_s = 0.0;
};

/// Triangles first_triangle .. first_triangle + triangle_count - 1 of Model::mesh move rigidly with
/// `node` (the deepest animated node above them, or their own node): their rest positions are
/// mapped by model_from_node(t) * model_from_node(rest)^-1.
struct AnimationPart {
    std::uint32_t node = 0;
    std::uint32_t first_triangle = 0;
    std::uint32_t triangle_count = 0;
};

/// Model::mesh holds every triangle at rest (no animation playing); this says how parts of it move.
/// Triangles in no part never move relative to the model.
struct Animation {
    std::vector<AnimationNode> nodes;
    std::vector<AnimationPart> parts;
    std::vector<AnimationClip> clips;
};

/// Which of a model's animations an object plays, all looping from the scenario's time 0.
struct AnimationChoice {
    enum class Mode : std::uint8_t { all, none, one } mode = Mode::all;
    std::uint32_t clip = 0;  ///< for Mode::one: index into Animation::clips

    bool plays(std::uint32_t clip_index) const {
        return mode == Mode::all || (mode == Mode::one && clip == clip_index);
    }
};

/// Every node's model_from_node at rest (no animation playing), by node index.
std::vector<Eigen::Affine3d> rest_model_from_node(const Animation& animation);

/// The model's triangle indices by part: [0] those in no part (they move with the model), [1 + p]
/// those of part p, each in increasing order.
std::vector<std::vector<std::uint32_t>> triangles_by_part(const Model& model);

/// True when the choice makes some part of the model move.
bool animates(const Model& model, const AnimationChoice& choice);

/// For each of the model's animation parts, in order, model_from_rest at `time_s`: where the
/// part's rest vertices go in the model frame. Samplers interpolate as glTF says (linear rotation
/// by shortest-path slerp); a clip's time is time_s modulo its duration.
void part_motions(const Model& model, const AnimationChoice& choice, double time_s, std::vector<Eigen::Affine3d>& out);

/// part_motions for one model and choice at many times (a ray's own time each): the rest pose is
/// resolved once. The model must outlive it; `at` may run on several threads at once.
class PartMotions {
public:
    PartMotions(const Model& model, const AnimationChoice& choice);
    /// Every part's motion, as part_motions gives them.
    void at(double time_s, std::vector<Eigen::Affine3d>& out) const;
    /// One part's motion, the same to the bit, from its own node's chain and channels only.
    Eigen::Affine3d at(std::size_t part, double time_s) const;

private:
    struct Link {
        std::uint32_t node;
        std::vector<std::pair<const AnimationClip*, const AnimationChannel*>> channels;
    };
    const Animation* animation_;
    AnimationChoice choice_;
    std::vector<Eigen::Affine3d> rest_from_model_;  // each part's rest placement, inverted
    std::vector<std::vector<Link>> chains_;         // each part's node and its ancestors, root first
};

/// A box in the model frame holding the whole mesh at every time of the chosen animations:
/// sampled densely over each clip's loop and padded for what lies between samples.
Eigen::AlignedBox3d animated_bounds(const Model& model, const AnimationChoice& choice);


}  // namespace ladarsim::scene
