#include "ladarsim/raytrace/traced_scene.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include <embree3/rtcore.h>

namespace ladarsim::raytrace {
namespace {

// Owning handles: Embree objects are reference counted C handles.
struct DeviceDeleter { void operator()(RTCDeviceTy* d) const { rtcReleaseDevice(d); } };
struct SceneDeleter { void operator()(RTCSceneTy* s) const { rtcReleaseScene(s); } };
struct GeometryDeleter { void operator()(RTCGeometryTy* g) const { rtcReleaseGeometry(g); } };
using Device = std::unique_ptr<RTCDeviceTy, DeviceDeleter>;
using EmbreeScene = std::unique_ptr<RTCSceneTy, SceneDeleter>;
using Geometry = std::unique_ptr<RTCGeometryTy, GeometryDeleter>;

enum class GeometryKind { static_mesh, moving_instance, discs };

// What a geometry id of the top scene stands for.
struct TopGeometry {
    GeometryKind kind;
    Geometry geometry;
    const scene::SceneObject* object = nullptr;  // null for the background discs
    const float* vertices = nullptr;              // static meshes: Embree's own vertex buffer (x y z per vertex)
};

// One BVH per distinct model, instanced by every moving object that uses it.
struct ModelBvh {
    EmbreeScene scene;
    const scene::Model* model;
};

using Matrix34 = Eigen::Matrix<double, 3, 4>;

// Ray-triangle distance in double precision (Moller-Trumbore). Embree's float t carries a relative
// error of a few 1e-7, i.e. millimetres at 2 km; the vertices it tested are exact floats, so
// repeating the intersection in double recovers the range to well below a millimetre.
std::optional<double> triangle_distance(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& a,
                                        const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const Eigen::Vector3d e1 = b - a, e2 = c - a;
    const Eigen::Vector3d p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-300) return std::nullopt;
    const Eigen::Vector3d s = o - a;
    return e2.dot(s.cross(e1)) / det;
}

Matrix34 to_matrix(const float* column_major) {
    Matrix34 m;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r) m(r, c) = column_major[3 * c + r];
    return m;
}

}  // namespace

struct TracedScene::Impl {
    Eigen::Vector3d origin_world;
    Device device;
    EmbreeScene top;
    EmbreeScene volumes;  // fog and cloud boundaries, traced only by volumes_along
    std::vector<const scene::SceneObject*> volume_objects;  // by geometry id in `volumes`
    std::vector<const float*> volume_vertices;
    std::vector<ModelBvh> models;
    std::vector<TopGeometry> geometries;  // by Embree geometry id in the top scene
    std::map<const scene::Model*, std::size_t> model_index;
    const scene::BackgroundMap* background = nullptr;
    // One per mesh object: its bounds, and for a moving object its transform at each motion step.
    struct BoundsTrack {
        const scene::SceneObject* object;
        ObjectBounds bounds;
        std::vector<Matrix34> step_world_from_model;
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
    void intersect(std::span<const Ray> rays, std::vector<RTCRayHit>& buffer) const {
        buffer.resize(rays.size());
        for (std::size_t i = 0; i < rays.size(); ++i) to_embree(rays[i], buffer[i]);
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        rtcIntersect1M(top.get(), &context, buffer.data(), static_cast<unsigned>(rays.size()), sizeof(RTCRayHit));
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

    Impl(const scene::Scene& scene, const Eigen::Vector3d& origin) : origin_world(origin) {
        device.reset(rtcNewDevice(nullptr));
        if (!device) throw std::runtime_error("Embree: could not create a device (unsupported CPU?)");
        rtcSetDeviceErrorFunction(device.get(), &Impl::on_error, this);
        top.reset(rtcNewScene(device.get()));
        // Dynamic: Embree then keeps one BVH per geometry and rebuilds only the instances that
        // move with each new time window, not the static terrain or the background map.
        rtcSetSceneFlags(top.get(), RTC_SCENE_FLAG_DYNAMIC);
        volumes.reset(rtcNewScene(device.get()));
        // Watertight triangle tests: a ray must not slip through the edge between two boundary
        // triangles and lose a crossing of a cloud. Volume boundaries are few: the care costs little.
        rtcSetSceneFlags(volumes.get(), RTC_SCENE_FLAG_ROBUST);
        for (const scene::SceneObject& object : scene.objects) {
            if (!object.model || object.model->mesh.triangles.empty()) continue;
            add_bounds(object);
            if (object.model->is_volume()) add_volume(object);
            else if (object.trajectory.is_static()) add_static_mesh(object);
            else add_moving_instance(object);
        }
        if (scene.background && !scene.background->points_world.empty()) add_discs(*scene.background);
        rtcCommitScene(volumes.get());
        find_volumes_holding_origin();
        check("building the scene");
        set_time_window(0.0, 0.0, 2);
    }

    void attach(TopGeometry entry) {
        rtcCommitGeometry(entry.geometry.get());
        // Embree numbers the geometries of a fresh scene 0, 1, 2, ... in attachment order.
        const unsigned id = rtcAttachGeometry(top.get(), entry.geometry.get());
        if (id != geometries.size()) throw std::logic_error("Embree geometry ids are not sequential");
        geometries.push_back(std::move(entry));
    }

    // Fills an Embree triangle geometry from a mesh, vertices mapped by `transform`.
    Geometry triangle_geometry(const scene::TriangleMesh& mesh, const Matrix34& transform, float** vertex_buffer) {
        Geometry g(rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE));
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g.get(), RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                              3 * sizeof(float), mesh.positions.size()));
        auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g.get(), RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), mesh.triangles.size()));
        check("allocating a triangle mesh");
        for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
            const Eigen::Vector3d p = transform * mesh.positions[i].cast<double>().homogeneous();
            for (int k = 0; k < 3; ++k) v[3 * i + k] = static_cast<float>(p[k]);
        }
        for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
            for (int k = 0; k < 3; ++k) t[3 * i + k] = mesh.triangles[i][k];
        if (vertex_buffer) *vertex_buffer = v;
        return g;
    }

    // world - origin, as the affine map applied to model coordinates.
    Matrix34 relative_from_model(const scene::SceneObject& object, double time_s) const {
        Eigen::Isometry3d pose = object.trajectory.at(time_s).world_from_object();
        pose.translation() -= origin_world;
        Eigen::Affine3d m = pose * Eigen::Scaling(object.scale);
        return m.matrix().topRows<3>();
    }

    Matrix34 world_from_model(const scene::SceneObject& object, double time_s) const {
        Matrix34 m = relative_from_model(object, time_s);
        m.col(3) += origin_world;
        return m;
    }

    void add_bounds(const scene::SceneObject& object) {
        ObjectBounds b;
        b.object_id = object.id;
        b.box_model = object.model->bounds().cast<double>();
        b.radius_m = 0.5 * object.scale * b.box_model.sizes().norm();
        b.volume = object.model->is_volume();
        b.moving = !b.volume && !object.trajectory.is_static();
        b.world_from_model = world_from_model(object, 0.0);
        b.centre_world = b.world_from_model * b.box_model.center().homogeneous();
        bounds.push_back({&object, b, {}});
    }

    void add_static_mesh(const scene::SceneObject& object) {
        TopGeometry entry{GeometryKind::static_mesh, nullptr, &object, nullptr};
        float* vertices = nullptr;
        entry.geometry = triangle_geometry(object.model->mesh, relative_from_model(object, 0.0), &vertices);
        entry.vertices = vertices;
        attach(std::move(entry));
    }

    void add_volume(const scene::SceneObject& object) {
        float* vertices = nullptr;
        Geometry g = triangle_geometry(object.model->mesh, relative_from_model(object, 0.0), &vertices);
        rtcSetGeometryIntersectFilterFunction(g.get(), &Impl::collect_crossing);
        rtcCommitGeometry(g.get());
        const unsigned id = rtcAttachGeometry(volumes.get(), g.get());
        if (id != volume_objects.size()) throw std::logic_error("Embree geometry ids are not sequential");
        volume_objects.push_back(&object);
        volume_vertices.push_back(vertices);
        volume_geometries.push_back(std::move(g));
    }

    std::vector<Geometry> volume_geometries;

    // Every boundary a ray crosses, gathered in one traversal: the filter records each candidate
    // hit and rejects it so that Embree goes on. (Stepping from hit to hit instead skips a second
    // boundary at the same distance, e.g. where a ray grazes an edge, entering and leaving at once.)
    struct Crossing {
        std::uint32_t geometry;
        std::uint32_t prim;
    };
    struct CrossingContext {
        RTCIntersectContext context;  // first: Embree hands callbacks a pointer to it
        std::vector<Crossing>* crossings;
    };
    static void collect_crossing(const RTCFilterFunctionNArguments* args) {
        auto* context = reinterpret_cast<const CrossingContext*>(args->context);
        for (unsigned i = 0; i < args->N; ++i) {
            if (args->valid[i] != -1) continue;
            context->crossings->push_back({RTCHitN_geomID(args->hit, args->N, i), RTCHitN_primID(args->hit, args->N, i)});
            args->valid[i] = 0;
        }
    }

    struct Boundary {
        double range_m;  // in double, from the triangle itself
        bool entering;
        std::uint32_t geometry, prim;
    };
    /// The volume boundaries along a ray (origin relative to origin_world), nearest first, into
    /// `boundaries` (reused: this runs per sub-ray in beams that meet a medium).
    void boundaries_along(const Eigen::Vector3d& o, const Ray& ray, std::vector<Boundary>& boundaries) const {
        thread_local std::vector<Crossing> crossings;
        crossings.clear();
        CrossingContext context;
        rtcInitIntersectContext(&context.context);
        context.crossings = &crossings;
        RTCRayHit rh;
        to_embree(ray, rh);
        rtcIntersect1(volumes.get(), &context.context, &rh);
        boundaries.clear();
        for (const Crossing& c : crossings) {
            const auto& tri = volume_objects[c.geometry]->model->mesh.triangles[c.prim];
            const float* v = volume_vertices[c.geometry];
            Eigen::Vector3d corner[3];
            for (int k = 0; k < 3; ++k) corner[k] = Eigen::Vector3d(v[3 * tri[k]], v[3 * tri[k] + 1], v[3 * tri[k] + 2]);
            const auto range = triangle_distance(o, ray.direction, corner[0], corner[1], corner[2]);
            if (!range) continue;  // degenerate triangle
            const Eigen::Vector3d normal = (corner[1] - corner[0]).cross(corner[2] - corner[0]);
            boundaries.push_back({std::max(*range, 0.0), normal.dot(ray.direction) < 0.0, c.geometry, c.prim});
        }
        std::sort(boundaries.begin(), boundaries.end(), [](const Boundary& a, const Boundary& b) { return a.range_m < b.range_m; });
    }

    // Whether the sensor (origin_world, where every beam starts) sits inside each volume, decided
    // once by parity along three skew directions (a majority, in case one grazes an edge). Deciding
    // it per ray from the order of its crossings fails on rays grazing a silhouette, where float
    // vertices can sort the exit a few millimetres before the entry.
    std::vector<bool> origin_inside;
    void find_volumes_holding_origin() {
        origin_inside.assign(volume_objects.size(), false);
        if (volume_objects.empty()) return;
        std::vector<int> votes(volume_objects.size(), 0);
        std::vector<Boundary> boundaries;
        for (const Eigen::Vector3d& d : {Eigen::Vector3d(0.5377, 0.1834, 0.8229), Eigen::Vector3d(-0.3094, 0.9281, -0.2070),
                                         Eigen::Vector3d(0.7071, -0.5000, -0.5000)}) {
            Ray ray;
            ray.origin_world = origin_world;
            ray.direction = d.normalized();
            ray.max_range_m = 1e7;
            std::vector<int> parity(volume_objects.size(), 0);
            boundaries_along(Eigen::Vector3d::Zero(), ray, boundaries);
            for (const Boundary& b : boundaries) parity[b.geometry] ^= 1;
            for (std::size_t g = 0; g < parity.size(); ++g) votes[g] += parity[g];
        }
        for (std::size_t g = 0; g < votes.size(); ++g) origin_inside[g] = votes[g] >= 2;
    }

    void add_moving_instance(const scene::SceneObject& object) {
        auto [it, inserted] = model_index.emplace(object.model.get(), models.size());
        if (inserted) {
            EmbreeScene child(rtcNewScene(device.get()));
            rtcSetSceneBuildQuality(child.get(), RTC_BUILD_QUALITY_HIGH);
            Geometry g = triangle_geometry(object.model->mesh, Matrix34::Identity(), nullptr);
            rtcCommitGeometry(g.get());
            rtcAttachGeometry(child.get(), g.get());
            rtcCommitScene(child.get());
            check("building a model's BVH");
            models.push_back(ModelBvh{std::move(child), object.model.get()});
        }
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
        attach(TopGeometry{GeometryKind::discs, std::move(g), nullptr, nullptr});
    }

    void set_time_window(double begin_s, double end_s, int motion_steps) {
        if (!(end_s >= begin_s) || !std::isfinite(begin_s) || !std::isfinite(end_s))
            throw std::invalid_argument("TracedScene: time window must be finite with end >= begin");
        if (motion_steps < 2) throw std::invalid_argument("TracedScene: motion_steps must be at least 2");
        window_begin_s = begin_s;
        window_length_s = end_s - begin_s;
        window_id = ++windows_set;
        for (BoundsTrack& track : bounds) {
            if (!track.bounds.moving) continue;
            track.step_world_from_model.resize(static_cast<std::size_t>(motion_steps));
            for (int step = 0; step < motion_steps; ++step)
                track.step_world_from_model[static_cast<std::size_t>(step)] =
                    world_from_model(*track.object, begin_s + window_length_s * step / (motion_steps - 1));
        }
        for (auto& entry : geometries) {
            if (entry.kind != GeometryKind::moving_instance) continue;
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
        rtcCommitScene(top.get());
        check("committing the scene");
    }

    float embree_time(double time_s) const {
        if (window_length_s <= 0.0) return 0.0f;
        return static_cast<float>(std::clamp((time_s - window_begin_s) / window_length_s, 0.0, 1.0));
    }

    void to_embree(const Ray& ray, RTCRayHit& rh) const {
        rh = RTCRayHit{};
        const Eigen::Vector3d o = ray.origin_world - origin_world;
        rh.ray.org_x = static_cast<float>(o.x());
        rh.ray.org_y = static_cast<float>(o.y());
        rh.ray.org_z = static_cast<float>(o.z());
        rh.ray.dir_x = static_cast<float>(ray.direction.x());
        rh.ray.dir_y = static_cast<float>(ray.direction.y());
        rh.ray.dir_z = static_cast<float>(ray.direction.z());
        rh.ray.tnear = 0.0f;
        rh.ray.tfar = static_cast<float>(ray.max_range_m);
        rh.ray.time = embree_time(ray.time_s);
        rh.ray.mask = 0xFFFFFFFFu;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    }

    std::optional<Hit> to_hit(const Ray& ray, const RTCRayHit& rh) const {
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
        const bool instanced = rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID;
        const TopGeometry& entry = geometries[instanced ? rh.hit.instID[0] : rh.hit.geomID];
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
            const auto& tri = model.mesh.triangles[prim];
            hit.object_id = object.id;
            hit.object_class = object.object_class;
            hit.material = model.mesh.triangle_material[prim];
            hit.reflectance = static_cast<float>(model.materials[hit.material].reflectance);
            Eigen::Vector3d v[3];
            if (entry.kind == GeometryKind::static_mesh) {
                for (int k = 0; k < 3; ++k)
                    v[k] = Eigen::Vector3d(entry.vertices[3 * tri[k]], entry.vertices[3 * tri[k] + 1], entry.vertices[3 * tri[k] + 2]);
            } else {
                // The instance's transform at this ray's time, as Embree interpolated it; a beam's
                // sub-rays share one time, so the last one is kept.
                thread_local struct {
                    RTCGeometry geometry = nullptr;
                    float time = 0.0f;
                    std::uint64_t window = 0;
                    Matrix34 m;
                } last;
                if (last.geometry != entry.geometry.get() || last.time != rh.ray.time || last.window != window_id) {
                    float xfm[12];
                    rtcGetGeometryTransform(entry.geometry.get(), rh.ray.time, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
                    last = {entry.geometry.get(), rh.ray.time, window_id, to_matrix(xfm)};
                }
                const Matrix34& m = last.m;
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
    std::vector<VolumeSegment> segments;
    if (impl_->volume_objects.empty()) return segments;
    const Eigen::Vector3d o = ray.origin_world - impl_->origin_world;
    auto close = [&](std::uint32_t geometry, double enter_m, double exit_m, std::uint32_t prim) {
        const scene::SceneObject& object = *impl_->volume_objects[geometry];
        const scene::Material& m = object.model->materials[object.model->mesh.triangle_material[prim]];
        segments.push_back({object.id, enter_m, exit_m, m.extinction_per_m, m.backscatter_per_m_sr});
    };
    struct Open { std::uint32_t geometry; double enter_m; std::uint32_t prim; };
    std::vector<Open> open;
    const bool from_sensor = o.squaredNorm() < 1e-12;
    thread_local std::vector<Impl::Boundary> boundaries;
    impl_->boundaries_along(o, ray, boundaries);
    std::vector<std::uint32_t> met;  // volumes whose boundary this ray has crossed already
    for (std::uint32_t g = 0; g < impl_->volume_objects.size(); ++g)
        if (from_sensor && impl_->origin_inside[g]) open.push_back({g, 0.0, 0});
    for (const Impl::Boundary& b : boundaries) {
        const auto it = std::find_if(open.begin(), open.end(), [&](const Open& x) { return x.geometry == b.geometry; });
        const bool first = std::find(met.begin(), met.end(), b.geometry) == met.end();
        if (first) met.push_back(b.geometry);
        if (b.entering) {
            if (it == open.end()) open.push_back({b.geometry, b.range_m, b.prim});
        } else if (it != open.end()) {
            close(b.geometry, it->enter_m, b.range_m, b.prim);
            open.erase(it);
        } else if (first && !from_sensor) {
            close(b.geometry, 0.0, b.range_m, b.prim);  // a ray from elsewhere, starting inside
        }
        // else: a grazing ray's exit sorted before its entry, or one exit reported by both
        // triangles of an edge
    }
    for (const Open& x : open) close(x.geometry, x.enter_m, ray.max_range_m, x.prim);
    std::sort(segments.begin(), segments.end(), [](const VolumeSegment& a, const VolumeSegment& b) { return a.enter_m < b.enter_m; });
    return segments;
}

bool TracedScene::has_volumes() const { return !impl_->volume_objects.empty(); }

void TracedScene::object_bounds(double time_s, std::vector<ObjectBounds>& out) const {
    out.clear();
    const double u = impl_->embree_time(time_s);
    for (const Impl::BoundsTrack& track : impl_->bounds) {
        out.push_back(track.bounds);
        if (!track.bounds.moving) continue;
        const auto& m = track.step_world_from_model;
        const double f = u * static_cast<double>(m.size() - 1);
        const std::size_t i = std::min(static_cast<std::size_t>(f), m.size() - 2);
        ObjectBounds& b = out.back();
        b.world_from_model = m[i] + (f - static_cast<double>(i)) * (m[i + 1] - m[i]);
        b.centre_world = b.world_from_model * b.box_model.center().homogeneous();
    }
}

TracedScene::TracedScene(const scene::Scene& scene, const Eigen::Vector3d& origin_world)
    : impl_(std::make_unique<Impl>(scene, origin_world)) {}

TracedScene::~TracedScene() = default;

void TracedScene::set_time_window(double begin_s, double end_s, int motion_steps) {
    impl_->set_time_window(begin_s, end_s, motion_steps);
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
    if (results.size() != rays.size()) throw std::invalid_argument("TracedScene::trace: rays and results differ in size");
    impl_->log(rays);
    // Reused per thread: a frame traces one small stream per beam, and allocating each time costs
    // as much as tracing it.
    thread_local std::vector<RTCRayHit> buffer;
    impl_->intersect(rays, buffer);
    for (std::size_t i = 0; i < rays.size(); ++i) results[i] = impl_->to_hit(rays[i], buffer[i]);
}

void TracedScene::record_rays(std::vector<std::vector<Ray>>* log) { impl_->ray_log = log; }

std::size_t TracedScene::intersect_only(std::span<const Ray> rays) const {
    thread_local std::vector<RTCRayHit> buffer;
    impl_->intersect(rays, buffer);
    std::size_t hits = 0;
    for (const RTCRayHit& rh : buffer) hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    return hits;
}

const Eigen::Vector3d& TracedScene::origin_world() const { return impl_->origin_world; }

}  // namespace ladarsim::raytrace
