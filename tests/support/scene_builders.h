#pragma once
// Hand-built scenes for tests: shapes whose ranges and areas have closed forms.
#include <cmath>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "ladarsim/scene/animation.h"
#include "ladarsim/scene/procedural_models.h"
#include "ladarsim/scene/scene.h"

namespace ladarsim::test {

/// A square plate facing +-x at rest, turned about the vertical through its centre by a glTF
/// rotation channel (LINEAR: slerp) with these keys: (time in s, yaw in deg).
inline scene::Model turning_plate(double side_m, const std::vector<std::pair<double, double>>& keys) {
    scene::Model m = scene::make_plate(side_m, 0.5);
    auto animation = std::make_shared<scene::Animation>();
    animation->nodes.push_back(scene::AnimationNode{});
    animation->parts.push_back({0, 0, static_cast<std::uint32_t>(m.mesh.triangles.size())});
    scene::AnimationChannel turn;
    turn.path = scene::AnimationPath::rotation;
    turn.interpolation = scene::AnimationInterpolation::linear;
    for (const auto& [time_s, yaw_deg] : keys) {
        const Eigen::Quaterniond q(Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
        turn.times_s.push_back(time_s);
        turn.values.insert(turn.values.end(), {q.x(), q.y(), q.z(), q.w()});
    }
    animation->clips.push_back(scene::AnimationClip{"turn", {turn}, keys.back().first});
    m.animation = animation;
    return m;
}

/// A square plate in the model's y-z plane (facing -x and +x), side `side_m`, centred on the origin.
inline std::shared_ptr<const scene::Model> plate(double side_m, double reflectance) {
    return std::make_shared<scene::Model>(scene::make_plate(side_m, reflectance));
}

/// A regular `segments`-gon of circumradius `radius_m` in the model's y-z plane, facing +-x.
inline std::shared_ptr<const scene::Model> disc(double radius_m, int segments, double reflectance) {
    auto m = std::make_shared<scene::Model>();
    m->mesh.positions.push_back(Eigen::Vector3f::Zero());
    for (int i = 0; i < segments; ++i) {
        const double a = 2.0 * M_PI * i / segments;
        m->mesh.positions.emplace_back(0.0f, static_cast<float>(radius_m * std::cos(a)), static_cast<float>(radius_m * std::sin(a)));
    }
    for (int i = 0; i < segments; ++i)
        m->mesh.triangles.push_back({0u, static_cast<std::uint32_t>(1 + i), static_cast<std::uint32_t>(1 + (i + 1) % segments)});
    m->mesh.triangle_material.assign(static_cast<std::size_t>(segments), 0);
    m->materials = {scene::Material{"disc", reflectance}};
    return m;
}

/// A sphere of `radius_m` about the origin: an icosahedron subdivided `levels` times, every vertex
/// on the sphere. The flat facets lie inside it by at most radius * (1 - cos(theta)), theta the
/// largest angle between a vertex and its facet's centroid (see max_facet_sag).
inline std::shared_ptr<const scene::Model> icosphere(double radius_m, int levels, double reflectance) {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<Eigen::Vector3d> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                      {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (auto& p : v) p.normalize();
    std::vector<std::array<std::uint32_t, 3>> f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11},
                                                   {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                                   {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9},
                                                   {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoint;
        auto mid = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::minmax(a, b);
            auto [it, inserted] = midpoint.emplace(key, static_cast<std::uint32_t>(v.size()));
            if (inserted) v.push_back((v[a] + v[b]).normalized());
            return it->second;
        };
        std::vector<std::array<std::uint32_t, 3>> next;
        for (const auto& [a, b, c] : f) {
            const std::uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
            next.insert(next.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
        }
        f = std::move(next);
    }
    auto m = std::make_shared<scene::Model>();
    for (const auto& p : v) m->mesh.positions.push_back((radius_m * p).cast<float>());
    m->mesh.triangles = f;
    m->mesh.triangle_material.assign(f.size(), 0);
    m->materials = {scene::Material{"sphere", reflectance}};
    return m;
}

/// Largest distance between the sphere and a facet of `model` (an icosphere of `radius_m`).
inline double max_facet_sag(const scene::Model& model, double radius_m) {
    double worst = 0.0;
    for (const auto& tri : model.mesh.triangles) {
        const Eigen::Vector3d a = model.mesh.positions[tri[0]].cast<double>();
        const Eigen::Vector3d b = model.mesh.positions[tri[1]].cast<double>();
        const Eigen::Vector3d c = model.mesh.positions[tri[2]].cast<double>();
        const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
        worst = std::max(worst, radius_m - std::abs(n.dot(a)));  // the facet plane's distance from the centre
    }
    return worst;
}

inline scene::SceneObject object_at(std::uint32_t id, std::shared_ptr<const scene::Model> model, scene::Trajectory t,
                                    scene::ObjectClass object_class = scene::ObjectClass::drone) {
    scene::SceneObject o;
    o.id = id;
    o.object_class = object_class;
    o.model = std::move(model);
    o.trajectory = std::move(t);
    return o;
}

inline scene::Trajectory fixed_at(double x, double y, double z) {
    return scene::Trajectory::fixed(scene::Pose{{x, y, z}, Eigen::Quaterniond::Identity()});
}

/// Constant velocity without turning (a straight trajectory would turn a plate edge-on).
inline scene::Trajectory sliding(const Eigen::Vector3d& start, const Eigen::Vector3d& velocity_mps) {
    return scene::Trajectory::keyframes({{0.0, {start, Eigen::Quaterniond::Identity()}},
                                         {10.0, {start + 10.0 * velocity_mps, Eigen::Quaterniond::Identity()}}},
                                        scene::Interpolation::linear);
}

}  // namespace ladarsim::test
