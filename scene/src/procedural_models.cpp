#include "ladarsim/scene/procedural_models.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>
#include <string>
#include <system_error>

#include "ladarsim/core/input_error.h"
#include "ladarsim/scene/animation.h"
#include "ladarsim/scene/gltf_writer.h"

namespace ladarsim::scene {
namespace {

constexpr double kPi = std::numbers::pi;

/// Accumulates convex closed pieces into one model.
class ModelBuilder {
public:
    explicit ModelBuilder(std::string source) { model_.source = std::move(source); }

    std::uint32_t material(Material m) {
        model_.materials.push_back(std::move(m));
        return static_cast<std::uint32_t>(model_.materials.size()) - 1;
    }
    std::uint32_t material(const std::string& name, double reflectance) { return material(Material{name, reflectance}); }

    /// A convex, closed piece: every triangle is turned to face away from the piece's centroid,
    /// so callers list corners in any order.
    void convex_piece(const std::vector<Eigen::Vector3d>& vertices,
                      const std::vector<std::array<std::uint32_t, 3>>& triangles, std::uint32_t material) {
        Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
        for (const auto& v : vertices) centroid += v;
        centroid /= static_cast<double>(vertices.size());
        const auto base = static_cast<std::uint32_t>(model_.mesh.positions.size());
        for (const auto& v : vertices) model_.mesh.positions.push_back(v.cast<float>());
        for (auto t : triangles) {
            const Eigen::Vector3d &a = vertices[t[0]], &b = vertices[t[1]], &c = vertices[t[2]];
            if ((b - a).cross(c - a).dot((a + b + c) / 3.0 - centroid) < 0.0) std::swap(t[1], t[2]);
            model_.mesh.triangles.push_back({base + t[0], base + t[1], base + t[2]});
            model_.mesh.triangle_material.push_back(material);
        }
    }

    /// A box of the given half extents, placed by `pose`.
    void box(const Eigen::Affine3d& pose, const Eigen::Vector3d& half, std::uint32_t material) {
        std::vector<Eigen::Vector3d> v;
        for (int k = 0; k < 8; ++k)
            v.push_back(pose * Eigen::Vector3d((k & 1 ? 1 : -1) * half.x(), (k & 2 ? 1 : -1) * half.y(), (k & 4 ? 1 : -1) * half.z()));
        // Faces as corner quads: -x, +x, -y, +y, -z, +z.
        const std::uint32_t quads[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
        std::vector<std::array<std::uint32_t, 3>> t;
        for (const auto& q : quads) {
            t.push_back({q[0], q[1], q[2]});
            t.push_back({q[0], q[2], q[3]});
        }
        convex_piece(v, t, material);
    }

    /// A vertical frustum: radius r0 at z0, r1 at z0 + height (r1 = 0 makes a cone), about (x, y).
    void frustum(double x, double y, double z0, double height, double r0, double r1, int segments, std::uint32_t material) {
        std::vector<Eigen::Vector3d> v;
        std::vector<std::array<std::uint32_t, 3>> t;
        const auto n = static_cast<std::uint32_t>(segments);
        for (std::uint32_t i = 0; i < n; ++i) {
            const double a = 2.0 * kPi * i / n;
            v.emplace_back(x + r0 * std::cos(a), y + r0 * std::sin(a), z0);
        }
        const std::uint32_t bottom_centre = n;
        v.emplace_back(x, y, z0);
        if (r1 > 0.0) {
            for (std::uint32_t i = 0; i < n; ++i) {
                const double a = 2.0 * kPi * i / n;
                v.emplace_back(x + r1 * std::cos(a), y + r1 * std::sin(a), z0 + height);
            }
            v.emplace_back(x, y, z0 + height);
            const std::uint32_t top = n + 1, top_centre = 2 * n + 1;
            for (std::uint32_t i = 0; i < n; ++i) {
                const std::uint32_t j = (i + 1) % n;
                t.push_back({i, j, top + j});
                t.push_back({i, top + j, top + i});
                t.push_back({top_centre, top + i, top + j});
            }
        } else {
            v.emplace_back(x, y, z0 + height);
            const std::uint32_t apex = n + 1;
            for (std::uint32_t i = 0; i < n; ++i) t.push_back({i, (i + 1) % n, apex});
        }
        for (std::uint32_t i = 0; i < n; ++i) t.push_back({bottom_centre, (i + 1) % n, i});
        convex_piece(v, t, material);
    }

    /// An ellipsoid of semi-axes `radii` about `centre` (a UV sphere, `segments` around).
    void ellipsoid(const Eigen::Vector3d& centre, const Eigen::Vector3d& radii, int segments, std::uint32_t material) {
        std::vector<Eigen::Vector3d> v;
        std::vector<std::array<std::uint32_t, 3>> t;
        const int rings = segments / 2;
        v.push_back(centre + Eigen::Vector3d(0, 0, radii.z()));
        for (int r = 1; r < rings; ++r) {
            const double polar = kPi * r / rings;
            for (int k = 0; k < segments; ++k) {
                const double a = 2.0 * kPi * k / segments;
                v.push_back(centre + radii.cwiseProduct(Eigen::Vector3d(std::sin(polar) * std::cos(a), std::sin(polar) * std::sin(a),
                                                                        std::cos(polar))));
            }
        }
        v.push_back(centre - Eigen::Vector3d(0, 0, radii.z()));
        const auto n = static_cast<std::uint32_t>(segments);
        const auto ring = [&](int r, std::uint32_t k) { return 1 + static_cast<std::uint32_t>(r - 1) * n + k % n; };
        const auto bottom = static_cast<std::uint32_t>(v.size() - 1);
        for (std::uint32_t k = 0; k < n; ++k) {
            t.push_back({0, ring(1, k), ring(1, k + 1)});
            for (int r = 1; r + 1 < rings; ++r) {
                t.push_back({ring(r, k), ring(r + 1, k), ring(r + 1, k + 1)});
                t.push_back({ring(r, k), ring(r + 1, k + 1), ring(r, k + 1)});
            }
            t.push_back({bottom, ring(rings - 1, k + 1), ring(rings - 1, k)});
        }
        convex_piece(v, t, material);
    }

    std::uint32_t triangle_count() const { return static_cast<std::uint32_t>(model_.mesh.triangles.size()); }

    /// A node of the model's animation at `origin` (no rotation), carrying the triangles made
    /// since `first_triangle`, turning about `axis` through `angle_deg(t)` over one period, as
    /// `keys_per_period` LINEAR keys. Returns the node's index.
    std::uint32_t turning_part(const std::string& name, const Eigen::Vector3d& origin, std::uint32_t first_triangle,
                               const Eigen::Vector3d& axis, double period_s, int keys_per_period,
                               const std::function<double(double)>& angle_deg) {
        if (!animation_) animation_ = std::make_shared<Animation>();
        if (animation_->clips.empty()) animation_->clips.push_back(AnimationClip{name, {}, 0.0});
        const auto node = static_cast<std::uint32_t>(animation_->nodes.size());
        AnimationNode n;
        n.name = name;
        n.translation = origin;
        animation_->nodes.push_back(n);
        animation_->parts.push_back(AnimationPart{node, first_triangle, triangle_count() - first_triangle});
        AnimationChannel channel;
        channel.node = node;
        channel.path = AnimationPath::rotation;
        channel.interpolation = AnimationInterpolation::linear;
        for (int k = 0; k <= keys_per_period; ++k) {
            const double t = period_s * k / keys_per_period;
            const Eigen::Quaterniond q(Eigen::AngleAxisd(angle_deg(t) * kPi / 180.0, axis.normalized()));
            channel.times_s.push_back(t);
            channel.values.insert(channel.values.end(), {q.x(), q.y(), q.z(), q.w()});
        }
        AnimationClip& clip = animation_->clips.front();
        clip.duration_s = std::max(clip.duration_s, period_s);
        clip.channels.push_back(std::move(channel));
        return node;
    }

    Model take() {
        model_.animation = std::move(animation_);
        return std::move(model_);
    }
    Model& model() { return model_; }

private:
    Model model_;
    std::shared_ptr<Animation> animation_;
};

}  // namespace

Model make_quadcopter() {
    ModelBuilder b("procedural:quadcopter");
    const std::uint32_t shell = b.material("white_plastic", 0.6);
    const std::uint32_t black = b.material("black_plastic", 0.06);
    const double rotor_radius = 0.06, arm_reach = 0.15 - rotor_radius;  // rotor tips at +-0.15 m
    const double hub_z = 0.032;
    b.box(Eigen::Affine3d::Identity(), {0.05, 0.05, 0.025}, shell);
    for (int k = 0; k < 4; ++k) {
        const double angle = kPi / 4.0 + k * kPi / 2.0;
        const double mx = arm_reach * std::sqrt(2.0) * std::cos(angle), my = arm_reach * std::sqrt(2.0) * std::sin(angle);
        // Motor positions sit on the diagonals at (+-reach, +-reach); arms reach from the body to them.
        const double length = std::hypot(mx, my);
        Eigen::Affine3d arm = Eigen::Affine3d::Identity();
        arm.rotate(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()));
        arm.translate(Eigen::Vector3d(0.5 * length, 0.0, 0.0));
        b.box(arm, {0.5 * length, 0.006, 0.005}, shell);
        b.frustum(mx, my, 0.0, 0.03, 0.014, 0.014, 16, black);
        // Two blades; at rest along x on one diagonal and along y on the other, so that the
        // tips reach +-0.15 m on both axes. Neighbouring rotors turn opposite ways.
        const std::uint32_t first = b.triangle_count();
        Eigen::Affine3d blade = Eigen::Affine3d::Identity();
        blade.translate(Eigen::Vector3d(mx, my, hub_z));
        blade.rotate(Eigen::AngleAxisd(k % 2 == 0 ? 0.0 : kPi / 2.0, Eigen::Vector3d::UnitZ()));
        b.box(blade, {rotor_radius, 0.008, 0.002}, black);
        const double direction = k % 2 == 0 ? 1.0 : -1.0;
        b.turning_part("rotor " + std::to_string(k), {mx, my, hub_z}, first, Eigen::Vector3d::UnitZ(),
                       1.0 / kRotorRevolutionsPerSecond, 4, [direction](double t) { return direction * 360.0 * kRotorRevolutionsPerSecond * t; });
    }
    return b.take();
}

Model make_terrain() {
    ModelBuilder b("procedural:terrain");
    const std::uint32_t ground = b.material("grass_soil", 0.3);
    const double x0 = -100.0, x1 = 3000.0, y0 = -600.0, y1 = 600.0, step = 20.0;
    const int nx = static_cast<int>(std::lround((x1 - x0) / step)) + 1, ny = static_cast<int>(std::lround((y1 - y0) / step)) + 1;
    auto height = [](double x, double y) {
        double h = 1.0 * std::sin(2.0 * kPi * x / 370.0) * std::sin(2.0 * kPi * y / 290.0) +
                   0.8 * std::sin(2.0 * kPi * (x + y) / 530.0);
        if (x > 2000.0 && x < 2800.0) {
            const double crest = 115.0 + 35.0 * std::sin(2.0 * kPi * y / 900.0);  // 80..150 m along the ridge
            const double s = std::sin(kPi * (x - 2000.0) / 800.0);
            h += crest * s * s;
        }
        return h;
    };
    Model& m = b.model();
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j) {
            const double x = x0 + step * i, y = y0 + step * j;
            m.mesh.positions.emplace_back(static_cast<float>(x), static_cast<float>(y), static_cast<float>(height(x, y)));
        }
    auto node = [ny](int i, int j) { return static_cast<std::uint32_t>(i * ny + j); };
    for (int i = 0; i + 1 < nx; ++i)
        for (int j = 0; j + 1 < ny; ++j) {
            // Counter-clockwise seen from above: normals point up.
            m.mesh.triangles.push_back({node(i, j), node(i + 1, j), node(i + 1, j + 1)});
            m.mesh.triangles.push_back({node(i, j), node(i + 1, j + 1), node(i, j + 1)});
            m.mesh.triangle_material.insert(m.mesh.triangle_material.end(), 2, ground);
        }
    return b.take();
}

Model make_plate(double side_m, double reflectance) {
    ModelBuilder b("procedural:plate");
    const std::uint32_t m = b.material("plate", reflectance);
    const float h = static_cast<float>(0.5 * side_m);
    Model& model = b.model();
    model.mesh.positions = {{0, -h, -h}, {0, h, -h}, {0, h, h}, {0, -h, h}};
    model.mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    model.mesh.triangle_material = {m, m};
    return b.take();
}

Model make_sphere(double diameter_m, double reflectance) {
    ModelBuilder b("procedural:sphere");
    const std::uint32_t m = b.material("sphere", reflectance);
    const double r = 0.5 * diameter_m;
    b.ellipsoid(Eigen::Vector3d::Zero(), {r, r, r}, 32, m);
    return b.take();
}

Model make_box_building(double length_m, double width_m, double height_m) {
    ModelBuilder b("procedural:building");
    const std::uint32_t concrete = b.material("concrete", 0.35);
    Eigen::Affine3d pose = Eigen::Affine3d::Identity();
    pose.translate(Eigen::Vector3d(0.0, 0.0, 0.5 * height_m));
    b.box(pose, {0.5 * length_m, 0.5 * width_m, 0.5 * height_m}, concrete);
    return b.take();
}

Model make_tree(double height_m) {
    ModelBuilder b("procedural:tree");
    const std::uint32_t bark = b.material("bark", 0.25);
    const std::uint32_t foliage = b.material("foliage", 0.3);
    b.frustum(0.0, 0.0, 0.0, 0.35 * height_m, 0.02 * height_m, 0.015 * height_m, 12, bark);
    b.frustum(0.0, 0.0, 0.3 * height_m, 0.7 * height_m, 0.3 * height_m, 0.0, 24, foliage);
    return b.take();
}

Model make_bird(double wingspan_m) {
    ModelBuilder b("procedural:bird");
    // Feathers 0.2-0.6 at 1550 nm: a mid value for a grey-brown bird.
    const std::uint32_t feathers = b.material("feathers", 0.35);
    const double s = wingspan_m;
    b.ellipsoid(Eigen::Vector3d::Zero(), {0.22 * s, 0.06 * s, 0.06 * s}, 12, feathers);
    for (double side : {-1.0, 1.0}) {
        const std::uint32_t first = b.triangle_count();
        Eigen::Affine3d wing = Eigen::Affine3d::Identity();
        wing.translate(Eigen::Vector3d(0.0, side * 0.27 * s, 0.02 * s));
        b.box(wing, {0.07 * s, 0.23 * s, 0.005 * s}, feathers);
        // Hinged at the body; up is a turn about +x for the left wing (+y), about -x for the right.
        b.turning_part(side > 0 ? "left wing" : "right wing", {0.0, side * 0.04 * s, 0.02 * s}, first,
                       Eigen::Vector3d(side, 0.0, 0.0), 1.0 / kBirdWingbeatHz, 16, [](double t) {
                           return kWingMeanDeg + kWingAmplitudeDeg * std::sin(2.0 * kPi * kBirdWingbeatHz * t);
                       });
    }
    return b.take();
}

Model make_light_aircraft() {
    ModelBuilder b("procedural:light-aircraft");
    const std::uint32_t paint = b.material("white_paint", 0.6);
    Eigen::Affine3d fuselage = Eigen::Affine3d::Identity();
    b.box(fuselage, {3.6, 0.55, 0.65}, paint);
    Eigen::Affine3d wing = Eigen::Affine3d::Identity();
    wing.translate(Eigen::Vector3d(0.6, 0.0, 0.5));
    b.box(wing, {0.75, 5.5, 0.08}, paint);
    Eigen::Affine3d tail = Eigen::Affine3d::Identity();
    tail.translate(Eigen::Vector3d(-3.2, 0.0, 0.2));
    b.box(tail, {0.45, 1.7, 0.05}, paint);
    Eigen::Affine3d fin = Eigen::Affine3d::Identity();
    fin.translate(Eigen::Vector3d(-3.2, 0.0, 0.9));
    b.box(fin, {0.45, 0.04, 0.7}, paint);
    return b.take();
}

Model make_airliner() {
    ModelBuilder b("procedural:airliner");
    const std::uint32_t paint = b.material("white_paint", 0.6);
    // A320-like: 37.6 m long, 34 m span, 4 m fuselage.
    b.ellipsoid(Eigen::Vector3d::Zero(), {18.8, 2.0, 2.1}, 24, paint);
    Eigen::Affine3d wing = Eigen::Affine3d::Identity();
    wing.translate(Eigen::Vector3d(1.0, 0.0, -0.8));
    b.box(wing, {2.5, 17.0, 0.25}, paint);
    Eigen::Affine3d tail = Eigen::Affine3d::Identity();
    tail.translate(Eigen::Vector3d(-16.0, 0.0, 0.5));
    b.box(tail, {1.5, 6.0, 0.15}, paint);
    Eigen::Affine3d fin = Eigen::Affine3d::Identity();
    fin.translate(Eigen::Vector3d(-16.0, 0.0, 3.5));
    b.box(fin, {1.6, 0.15, 3.0}, paint);
    return b.take();
}

Model make_cloud(double diameter_m, double extinction_per_m) {
    ModelBuilder b("procedural:cloud");
    // A lidar ratio of 20 sr (extinction / backscatter) is typical of water clouds.
    const std::uint32_t m = b.material(Material{"cloud_water", 0.0, extinction_per_m, extinction_per_m / 20.0});
    b.ellipsoid(Eigen::Vector3d::Zero(), {0.5 * diameter_m, 0.5 * diameter_m, 0.3 * diameter_m}, 16, m);
    return b.take();
}

void write_default_assets(const std::filesystem::path& dir) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw InputError(dir.string(), "directory", ec.message());
    write_gltf(make_quadcopter(), dir / "quadcopter.glb");
    write_gltf(make_terrain(), dir / "terrain.glb");
    write_gltf(make_box_building(20.0, 12.0, 15.0), dir / "building.glb");
    write_gltf(make_tree(8.0), dir / "tree.glb");
    write_gltf(make_box_building(30.0, 30.0, 80.0), dir / "tower.glb");
    write_gltf(make_bird(0.4), dir / "bird.glb");
    write_gltf(make_light_aircraft(), dir / "light_aircraft.glb");
    write_gltf(make_airliner(), dir / "airliner.glb");
    write_gltf(make_cloud(60.0, 0.03), dir / "cloud.glb");
}

}  // namespace ladarsim::scene
