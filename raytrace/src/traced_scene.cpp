#include "ladarsim/raytrace/traced_scene.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <deque>
#include <map>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <embree3/rtcore.h>

#include "animated_part.h"
#include "embree_common.h"
#include "ladarsim/scene/animation.h"
#include "volume_boundaries.h"

namespace ladarsim::raytrace {
namespace {

enum class GeometryKind { static_mesh, moving_instance, discs };

// What a geometry id stands for: in the static scene a static mesh or the discs, in the top scene
// a moving instance.
struct TopGeometry {
    GeometryKind kind;
    Geometry geometry;
    const scene::SceneObject* object = nullptr;  // null for the background discs
    const float* vertices = nullptr;              // static meshes: Embree's own vertex buffer (x y z per vertex)
    // The model's triangle index of each primitive of the instanced BVH; null: the same index.
    const std::vector<std::uint32_t>* triangles = nullptr;
    // An animated object's part, placed by us rather than by Embree's transform; null otherwise.
    const AnimatedPart* animated = nullptr;
};

// One BVH per distinct model, instanced by every moving object that uses it; an animated model
// has one per animation part and one for the triangles in none.
struct ModelBvh {
    EmbreeScene scene;
    const scene::Model* model;
    std::vector<std::uint32_t> triangles;  // empty: the whole mesh
};

Matrix34 to_matrix(const float* column_major) {
    Matrix34 m;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r) m(r, c) = column_major[3 * c + r];
    return m;
}

}  // namespace

struct TracedScene::Impl {
    Eigen::Vector3d origin_world;
    // Where object_bounds_near's cones start, and how far from there they may (set_viewpoint).
    Eigen::Vector3d viewpoint_world;
    double viewpoint_radius_m = 0.0;
    Device device;
    // The static meshes and the background discs, built and committed once; the top scene holds
    // them as one instance with the identity transform, beside the moving instances, so that a new
    // time window rebuilds only the few moving instances' top-level BVH.
    EmbreeScene fixed;
    std::vector<TopGeometry> fixed_geometries;  // by Embree geometry id in `fixed`
    unsigned fixed_instance = RTC_INVALID_GEOMETRY_ID;  // its geometry id in the top scene
    EmbreeScene top;
    std::optional<VolumeBoundaries> volumes;  // fog and cloud, traced only by volumes_along
    std::deque<ModelBvh> models;  // a deque: instances point at their BVH's triangle list
    // Each animated object (its parts: the top geometries point at them) and its parts' geometry
    // ids in the top scene.
    struct Animated {
        std::unique_ptr<AnimatedObject> object;
        std::vector<unsigned> top_ids;
    };
    std::deque<Animated> animated;
    std::vector<TopGeometry> geometries;  // by Embree geometry id in the top scene (null entry: `fixed`)
    std::map<const scene::Model*, std::size_t> model_index;
    const scene::BackgroundMap* background = nullptr;
    // One per mesh object: its bounds, and for a moving object its transform at each motion step.
    struct BoundsTrack {
        const scene::SceneObject* object;
        ObjectBounds bounds;
        std::vector<Matrix34> step_world_from_model;
        // Its sphere over the whole time window, as seen from the viewpoint: the direction to its
        // centre, its angular radius, and whether it holds the viewpoint.
        Eigen::Vector3d window_direction = Eigen::Vector3d::UnitX();
        double window_angular_radius_rad = 0.0;
        bool window_holds_origin = false;
        // A static mesh's own sphere (not the window's) as seen from the viewpoint.
        double static_angular_radius_rad = 0.0;
    };
    std::vector<BoundsTrack> bounds;
    double window_begin_s = 0.0;
    double window_length_s = 0.0;
    // Which time window this is, unique across scenes: a transform cached under another is stale.
    std::uint64_t window_id = 0;
    static inline std::atomic<std::uint64_t> windows_set{0};

    std::mutex error_mutex;
    std::string last_error;
    std::mutex log_mutex;
    std::vector<std::vector<Ray>>* ray_log = nullptr;

    void log(std::span<const Ray> rays) {
        if (!ray_log) return;
        const std::lock_guard lock(log_mutex);
        ray_log->emplace_back(rays.begin(), rays.end());
    }

    // The sub-rays of one beam leave one point in nearly one direction: a coherent stream.
    void intersect(std::span<const Ray> rays, std::vector<RTCRayHit>& buffer, RTCScene scene) const {
        buffer.resize(rays.size());
        for (std::size_t i = 0; i < rays.size(); ++i) to_embree(rays[i], buffer[i]);
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        rtcIntersect1M(scene, &context, buffer.data(), static_cast<unsigned>(rays.size()), sizeof(RTCRayHit));
    }

    // Hit records of `rays` traced against `scene` (the top scene, or the static one alone).
    void trace_in(RTCScene scene, std::span<const Ray> rays, std::span<std::optional<Hit>> results) {
        if (results.size() != rays.size()) throw std::invalid_argument("TracedScene::trace: rays and results differ in size");
        log(rays);
        // Reused per thread: a frame traces one small stream per beam, and allocating each time
        // costs as much as tracing it.
        thread_local std::vector<RTCRayHit> buffer;
        intersect(rays, buffer, scene);
        for (std::size_t i = 0; i < rays.size(); ++i) results[i] = to_hit(rays[i], buffer[i]);
    }

    static void on_error(void* user, RTCError, const char* message) {
        auto* self = static_cast<Impl*>(user);
        const std::lock_guard lock(self->error_mutex);
        self->last_error = message ? message : "unknown error";
    }

    // Embree reports through a callback from C code; we turn it into an exception here, on our side.
    void check(const char* what) {
        if (rtcGetDeviceError(device.get()) == RTC_ERROR_NONE) return;
        const std::lock_guard lock(error_mutex);
        throw std::runtime_error(std::string("Embree error while ") + what + ": " + last_error);
    }

    Impl(const scene::Scene& scene, const Eigen::Vector3d& origin) : origin_world(origin), viewpoint_world(origin) {
        device.reset(rtcNewDevice(nullptr));
        if (!device) throw std::runtime_error("Embree: could not create a device (unsupported CPU?)");
        rtcSetDeviceErrorFunction(device.get(), &Impl::on_error, this);
        top.reset(rtcNewScene(device.get()));
        fixed.reset(rtcNewScene(device.get()));
        // Dynamic: Embree then keeps one BVH per geometry (as the top scene held them before the
        // static ones moved into a scene of their own; their hits are unchanged).
        rtcSetSceneFlags(top.get(), RTC_SCENE_FLAG_DYNAMIC);
        rtcSetSceneFlags(fixed.get(), RTC_SCENE_FLAG_DYNAMIC);
        volumes.emplace(device.get(), origin_world);
        for (const scene::SceneObject& object : scene.objects) {
            if (!object.model || object.model->mesh.triangles.empty()) continue;
            add_bounds(object);
            if (object.model->is_volume()) add_volume(object);
            else if (scene::animates(*object.model, object.animation)) add_animated_instances(object);
            else if (object.trajectory.is_static()) add_static_mesh(object);
            else add_moving_instance(object);
        }
        if (scene.background && !scene.background->points_world.empty()) add_discs(*scene.background);
        volumes->commit();
        if (!fixed_geometries.empty()) {
            rtcCommitScene(fixed.get());
            Geometry instance(rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_INSTANCE));
            rtcSetGeometryInstancedScene(instance.get(), fixed.get());
            const float identity[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
            rtcSetGeometryTransform(instance.get(), 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, identity);
            fixed_instance = static_cast<unsigned>(geometries.size());
            attach(TopGeometry{GeometryKind::static_mesh, std::move(instance), nullptr, nullptr});
        }
        check("building the scene");
        set_time_window(0.0, 0.0, 2);
    }

    void attach(TopGeometry entry) { attach_to(top.get(), geometries, std::move(entry)); }
    void attach_fixed(TopGeometry entry) { attach_to(fixed.get(), fixed_geometries, std::move(entry)); }

    static void attach_to(RTCScene scene, std::vector<TopGeometry>& by_id, TopGeometry entry) {
        rtcCommitGeometry(entry.geometry.get());
        // Embree numbers the geometries of a fresh scene 0, 1, 2, ... in attachment order.
        const unsigned id = rtcAttachGeometry(scene, entry.geometry.get());
        if (id != by_id.size()) throw std::logic_error("Embree geometry ids are not sequential");
        by_id.push_back(std::move(entry));
    }

    // Fills an Embree triangle geometry from a mesh, vertices mapped by `transform`; only the
    // triangles listed in `subset` when it is given.
    Geometry triangle_geometry(const scene::TriangleMesh& mesh, const Matrix34& transform, float** vertex_buffer,
                               const std::vector<std::uint32_t>* subset = nullptr) {
        Geometry g(rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE));
        const std::size_t triangles = subset ? subset->size() : mesh.triangles.size();
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g.get(), RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                              3 * sizeof(float), mesh.positions.size()));
        auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g.get(), RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), triangles));
        check("allocating a triangle mesh");
        for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
            const Eigen::Vector3d p = transform * mesh.positions[i].cast<double>().homogeneous();
            for (int k = 0; k < 3; ++k) v[3 * i + k] = static_cast<float>(p[k]);
        }
        for (std::size_t i = 0; i < triangles; ++i)
            for (int k = 0; k < 3; ++k) t[3 * i + k] = mesh.triangles[subset ? (*subset)[i] : i][k];
        if (vertex_buffer) *vertex_buffer = v;
        return g;
    }

    // world - origin, as the affine map applied to model coordinates.
    Matrix34 relative_from_model(const scene::SceneObject& object, double time_s) const {
        return raytrace::relative_from_model(object, origin_world, time_s);
    }

    Matrix34 world_from_model(const scene::SceneObject& object, double time_s) const {
        Matrix34 m = relative_from_model(object, time_s);
        m.col(3) += origin_world;
        return m;
    }

    void add_bounds(const scene::SceneObject& object) {
        ObjectBounds b;
        b.object_id = object.id;
        const bool animated = !object.model->is_volume() && scene::animates(*object.model, object.animation);
        b.box_model = animated ? scene::animated_bounds(*object.model, object.animation) : object.model->bounds().cast<double>();
        b.radius_m = 0.5 * object.scale * b.box_model.sizes().norm();
        b.volume = object.model->is_volume();
        b.moving = !b.volume && (!object.trajectory.is_static() || animated);
        b.world_from_model = world_from_model(object, 0.0);
        b.centre_world = b.world_from_model * b.box_model.center().homogeneous();
        bounds.push_back({&object, b, {}});
    }

    void add_static_mesh(const scene::SceneObject& object) {
        TopGeometry entry{GeometryKind::static_mesh, nullptr, &object, nullptr};
        float* vertices = nullptr;
        entry.geometry = triangle_geometry(object.model->mesh, relative_from_model(object, 0.0), &vertices);
        entry.vertices = vertices;
        attach_fixed(std::move(entry));
    }

    void add_volume(const scene::SceneObject& object) {
        float* vertices = nullptr;
        Geometry g = triangle_geometry(object.model->mesh, relative_from_model(object, 0.0), &vertices);
        volumes->add(object, std::move(g), vertices);
    }

    // A BVH of the given triangles of a model in its own frame (all of them when `subset` is empty).
    EmbreeScene model_bvh(const scene::Model& model, const std::vector<std::uint32_t>& subset) {
        EmbreeScene child(rtcNewScene(device.get()));
        rtcSetSceneBuildQuality(child.get(), RTC_BUILD_QUALITY_HIGH);
        Geometry g = triangle_geometry(model.mesh, Matrix34::Identity(), nullptr, subset.empty() ? nullptr : &subset);
        rtcCommitGeometry(g.get());
        rtcAttachGeometry(child.get(), g.get());
        rtcCommitScene(child.get());
        check("building a model's BVH");
        return child;
    }

    // One user geometry per animation part (and one for the triangles in none), each placed by the
    // object's pose and its part's motion at the ray's time.
    void add_animated_instances(const scene::SceneObject& object) {
        const scene::Model& model = *object.model;
        const auto& parts = model.animation->parts;
        auto [it, inserted] = model_index.emplace(&model, models.size());
        if (inserted) {
            // models[first + 0]: the triangles in no part; models[first + 1 + p]: part p.
            for (auto& list : scene::triangles_by_part(model)) {
                // An empty list stays empty: no BVH, and never instanced.
                EmbreeScene child = list.empty() ? EmbreeScene{} : model_bvh(model, list);
                models.push_back(ModelBvh{std::move(child), &model, std::move(list)});
            }
        }
        Animated& a = animated.emplace_back();
        a.object = std::make_unique<AnimatedObject>(object, origin_world);
        for (std::size_t k = 0; k <= parts.size(); ++k) {
            const ModelBvh& bvh = models[it->second + k];
            if (bvh.triangles.empty()) continue;
            const AnimatedPart& part = a.object->add_part(static_cast<int>(k) - 1, bvh.scene.get(), bvh.triangles);
            a.top_ids.push_back(static_cast<unsigned>(geometries.size()));
            attach(TopGeometry{GeometryKind::moving_instance, part.make_geometry(device.get()), &object, nullptr, &bvh.triangles,
                               &part});
        }
    }

    void add_moving_instance(const scene::SceneObject& object) {
        auto [it, inserted] = model_index.emplace(object.model.get(), models.size());
        if (inserted) models.push_back(ModelBvh{model_bvh(*object.model, {}), object.model.get(), {}});
        Geometry instance(rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_INSTANCE));
        rtcSetGeometryInstancedScene(instance.get(), models[it->second].scene.get());
        attach(TopGeometry{GeometryKind::moving_instance, std::move(instance), &object, nullptr});
    }

    void add_discs(const scene::BackgroundMap& map) {
        background = &map;
        const std::size_t n = map.points_world.size();
        Geometry g(rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_ORIENTED_DISC_POINT));
        auto* v = static_cast<float*>(
            rtcSetNewGeometryBuffer(g.get(), RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), n));
        auto* nrm = static_cast<float*>(
            rtcSetNewGeometryBuffer(g.get(), RTC_BUFFER_TYPE_NORMAL, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), n));
        check("allocating the background discs");
        for (std::size_t i = 0; i < n; ++i) {
            const Eigen::Vector3d p = map.points_world[i] - origin_world;
            for (int k = 0; k < 3; ++k) {
                v[4 * i + k] = static_cast<float>(p[k]);
                nrm[3 * i + k] = map.normals[i][k];
            }
            v[4 * i + 3] = map.radii_m[i];
        }
        attach_fixed(TopGeometry{GeometryKind::discs, std::move(g), nullptr, nullptr});
    }

    void set_time_window(double begin_s, double end_s, int motion_steps) {
        if (!(end_s >= begin_s) || !std::isfinite(begin_s) || !std::isfinite(end_s))
            throw std::invalid_argument("TracedScene: time window must be finite with end >= begin");
        if (motion_steps < 2) throw std::invalid_argument("TracedScene: motion_steps must be at least 2");
        window_begin_s = begin_s;
        window_length_s = end_s - begin_s;
        window_id = ++windows_set;
        for (BoundsTrack& track : bounds) {
            if (track.bounds.moving) {
                track.step_world_from_model.resize(static_cast<std::size_t>(motion_steps));
                for (int step = 0; step < motion_steps; ++step)
                    track.step_world_from_model[static_cast<std::size_t>(step)] =
                        world_from_model(*track.object, begin_s + window_length_s * step / (motion_steps - 1));
            }
            set_window_sphere(track);
        }
        for (auto& entry : geometries) {
            if (entry.kind != GeometryKind::moving_instance) continue;
            if (entry.animated) continue;
            RTCGeometry g = entry.geometry.get();
            rtcSetGeometryTimeStepCount(g, static_cast<unsigned>(motion_steps));
            for (int step = 0; step < motion_steps; ++step) {
                const double t = begin_s + window_length_s * step / (motion_steps - 1);
                const Matrix34 m = relative_from_model(*entry.object, t);
                float xfm[12];
                for (int c = 0; c < 4; ++c)
                    for (int r = 0; r < 3; ++r) xfm[3 * c + r] = static_cast<float>(m(r, c));
                rtcSetGeometryTransform(g, static_cast<unsigned>(step), RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
            }
            rtcCommitGeometry(g);
        }
        for (Animated& a : animated) {
            a.object->set_window(begin_s, window_length_s);
            for (const unsigned id : a.top_ids) rtcCommitGeometry(geometries[id].geometry.get());
        }
        rtcCommitScene(top.get());
        check("committing the scene");
    }

    // A moving object's centre at any time of the window is a linear interpolation between two
    // motion steps' centres (its radius unchanged): a sphere around the steps' centres, grown by
    // the object's radius, holds it throughout.
    void set_window_sphere(BoundsTrack& track) const {
        const Eigen::Vector3d centre_model = track.bounds.box_model.center();
        Eigen::AlignedBox3d centres;
        if (track.bounds.moving) {
            for (const Matrix34& m : track.step_world_from_model) centres.extend(m * centre_model.homogeneous());
        } else {
            centres.extend(track.bounds.centre_world);
        }
        const Eigen::Vector3d centre = centres.center();
        // Padded by a millionth for the rounding of the per-ray placement it must hold.
        const double radius = (0.5 * centres.sizes().norm() + track.bounds.radius_m) * (1.0 + 1e-6) + 1e-9 + viewpoint_radius_m;
        const Eigen::Vector3d to_centre = centre - viewpoint_world;
        const double distance = to_centre.norm();
        track.window_holds_origin = distance <= radius;
        track.window_direction = track.window_holds_origin ? Eigen::Vector3d::UnitX() : Eigen::Vector3d(to_centre / distance);
        track.window_angular_radius_rad = track.window_holds_origin ? std::numbers::pi : std::asin(radius / distance);
        const double own_distance = (track.bounds.centre_world - viewpoint_world).norm();
        track.static_angular_radius_rad = own_distance <= track.bounds.radius_m ? std::numbers::pi / 2.0
                                                                                : std::asin(track.bounds.radius_m / own_distance);
    }

    // A track's bounds at Embree's time `u` (0 to 1 over the window), appended to `out`.
    void push_bounds(std::size_t track_index, double u, std::vector<ObjectBounds>& out) const {
        const BoundsTrack& track = bounds[track_index];
        out.push_back(track.bounds);
        if (!track.bounds.moving) return;
        const auto& m = track.step_world_from_model;
        const double f = u * static_cast<double>(m.size() - 1);
        const std::size_t i = std::min(static_cast<std::size_t>(f), m.size() - 2);
        ObjectBounds& b = out.back();
        b.world_from_model = m[i] + (f - static_cast<double>(i)) * (m[i + 1] - m[i]);
        b.centre_world = b.world_from_model * b.box_model.center().homogeneous();
    }

    float embree_time(double time_s) const {
        if (window_length_s <= 0.0) return 0.0f;
        return static_cast<float>(std::clamp((time_s - window_begin_s) / window_length_s, 0.0, 1.0));
    }

    void to_embree(const Ray& ray, RTCRayHit& rh) const { raytrace::to_embree(ray, origin_world, embree_time(ray.time_s), rh); }

    // An instance's transform at Embree's time `u`, as Embree interpolates it; a beam's sub-rays
    // share one time, so the last one is kept.
    const Matrix34& instance_transform(RTCGeometry geometry, float u) const {
        thread_local struct {
            RTCGeometry geometry = nullptr;
            float time = 0.0f;
            std::uint64_t window = 0;
            Matrix34 m;
        } last;
        if (last.geometry != geometry || last.time != u || last.window != window_id) {
            float xfm[12];
            rtcGetGeometryTransform(geometry, u, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
            last = {geometry, u, window_id, to_matrix(xfm)};
        }
        return last.m;
    }

    std::optional<Hit> to_hit(const Ray& ray, const RTCRayHit& rh) const {
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
        // Every hit of the top scene is inside an instance: the static scene's, or a moving
        // object's; a hit of the static scene traced alone is in none.
        const unsigned instance = rh.hit.instID[0];
        const TopGeometry& entry = instance == fixed_instance || instance == RTC_INVALID_GEOMETRY_ID ? fixed_geometries[rh.hit.geomID]
                                                                                                      : geometries[instance];
        // The ray's origin in the relative frame, exactly (the float copy given to Embree is not).
        const Eigen::Vector3d o = ray.origin_world - origin_world;
        const Eigen::Vector3d& d = ray.direction;
        const unsigned prim = rh.hit.primID;

        Hit hit;
        hit.range_m = rh.ray.tfar;
        Eigen::Vector3d normal(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
        if (entry.kind == GeometryKind::discs) {
            hit.object_id = scene::kBackgroundObjectId;
            hit.object_class = scene::ObjectClass::background;
            hit.material = 0;
            hit.reflectance = background->reflectance[prim];
            const Eigen::Vector3d n = background->normals[prim].cast<double>();
            const double dn = d.dot(n);
            if (std::abs(dn) > 1e-12) hit.range_m = (background->points_world[prim] - ray.origin_world).dot(n) / dn;
            normal = n;
        } else {
            const scene::SceneObject& object = *entry.object;
            const scene::Model& model = *object.model;
            const std::uint32_t triangle = entry.triangles ? (*entry.triangles)[prim] : prim;
            const auto& tri = model.mesh.triangles[triangle];
            hit.object_id = object.id;
            hit.object_class = object.object_class;
            hit.material = model.mesh.triangle_material[triangle];
            hit.reflectance = static_cast<float>(model.materials[hit.material].reflectance);
            Eigen::Vector3d v[3];
            if (entry.kind == GeometryKind::static_mesh) {
                for (int k = 0; k < 3; ++k)
                    v[k] = Eigen::Vector3d(entry.vertices[3 * tri[k]], entry.vertices[3 * tri[k] + 1], entry.vertices[3 * tri[k] + 2]);
            } else {
                const Matrix34& m = entry.animated ? entry.animated->relative_from_model_at(rh.ray.time)
                                                   : instance_transform(entry.geometry.get(), rh.ray.time);
                for (int k = 0; k < 3; ++k) v[k] = m * model.mesh.positions[tri[k]].cast<double>().homogeneous();
            }
            if (const auto t = triangle_distance(o, d, v[0], v[1], v[2])) hit.range_m = *t;
            normal = (v[1] - v[0]).cross(v[2] - v[0]);
        }
        normal.normalize();
        double cos_incidence = d.dot(normal);
        if (cos_incidence > 0.0) normal = -normal;  // facing the ray
        hit.normal_world = normal.cast<float>();
        hit.cos_incidence = static_cast<float>(std::min(std::abs(cos_incidence), 1.0));
        return hit;
    }
};

std::vector<VolumeSegment> TracedScene::volumes_along(const Ray& ray) const {
    return impl_->volumes->along(ray, impl_->embree_time(ray.time_s));
}

void TracedScene::volumes_along(const Ray& ray, std::vector<VolumeSegment>& segments) const {
    impl_->volumes->along(ray, impl_->embree_time(ray.time_s), segments);
}

bool TracedScene::has_volumes() const { return !impl_->volumes->empty(); }

void TracedScene::object_bounds(double time_s, std::vector<ObjectBounds>& out) const {
    out.clear();
    const double u = impl_->embree_time(time_s);
    for (std::size_t k = 0; k < impl_->bounds.size(); ++k) impl_->push_bounds(k, u, out);
}

void TracedScene::object_bounds_near(const Eigen::Vector3d& axis_world, double half_angle_rad, double radius_factor,
                                     double time_s, double static_wider_rad, std::vector<ObjectBounds>& out) const {
    out.clear();
    // cos(half angle + factor x angular radius) of each object, per thread, for this window and cone.
    thread_local struct {
        std::uint64_t window = 0;
        double half_angle = -1.0, factor = -1.0;
        std::vector<double> cos_limit;
    } limits;
    if (limits.window != impl_->window_id || limits.half_angle != half_angle_rad || limits.factor != radius_factor) {
        limits.window = impl_->window_id;
        limits.half_angle = half_angle_rad;
        limits.factor = radius_factor;
        limits.cos_limit.clear();
        for (const Impl::BoundsTrack& track : impl_->bounds) {
            const double reach = half_angle_rad + radius_factor * track.window_angular_radius_rad;
            // -2: every direction (the sphere holds the sensor, or the cone reaches all round).
            limits.cos_limit.push_back(track.window_holds_origin || reach >= std::numbers::pi ? -2.0 : std::cos(reach));
        }
    }
    const double u = impl_->embree_time(time_s);
    for (std::size_t k = 0; k < impl_->bounds.size(); ++k) {
        // Less a hair for the rounding of the dot product near the limit.
        const Impl::BoundsTrack& track = impl_->bounds[k];
        if (!track.bounds.moving && !track.bounds.volume && track.static_angular_radius_rad >= static_wider_rad) continue;
        if (axis_world.dot(track.window_direction) < limits.cos_limit[k] - 1e-12) continue;
        impl_->push_bounds(k, u, out);
    }
}



TracedScene::TracedScene(const scene::Scene& scene, const Eigen::Vector3d& origin_world)
    : impl_(std::make_unique<Impl>(scene, origin_world)) {}

TracedScene::~TracedScene() = default;

void TracedScene::set_time_window(double begin_s, double end_s, int motion_steps) {
    impl_->set_time_window(begin_s, end_s, motion_steps);
}

void TracedScene::set_viewpoint(const Eigen::Vector3d& centre_world, double radius_m) {
    impl_->viewpoint_world = centre_world;
    impl_->viewpoint_radius_m = radius_m;
    impl_->window_id = ++Impl::windows_set;  // the cones' limits cached per window are stale
    for (Impl::BoundsTrack& track : impl_->bounds) impl_->set_window_sphere(track);
}

std::optional<Hit> TracedScene::trace(const Ray& ray) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    impl_->to_embree(ray, rh);
    impl_->log({&ray, 1});
    rtcIntersect1(impl_->top.get(), &context, &rh);
    return impl_->to_hit(ray, rh);
}

void TracedScene::trace(std::span<const Ray> rays, std::span<std::optional<Hit>> results) const {
    impl_->trace_in(impl_->top.get(), rays, results);
}

void TracedScene::trace_static(std::span<const Ray> rays, std::span<std::optional<Hit>> results) const {
    if (impl_->fixed_geometries.empty()) {
        if (results.size() != rays.size()) throw std::invalid_argument("TracedScene::trace_static: rays and results differ in size");
        std::fill(results.begin(), results.end(), std::nullopt);
        return;
    }
    impl_->trace_in(impl_->fixed.get(), rays, results);
}

void TracedScene::record_rays(std::vector<std::vector<Ray>>* log) { impl_->ray_log = log; }

std::size_t TracedScene::intersect_only(std::span<const Ray> rays) const {
    thread_local std::vector<RTCRayHit> buffer;
    impl_->intersect(rays, buffer, impl_->top.get());
    std::size_t hits = 0;
    for (const RTCRayHit& rh : buffer) hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    return hits;
}

const Eigen::Vector3d& TracedScene::origin_world() const { return impl_->origin_world; }

}  // namespace ladarsim::raytrace
