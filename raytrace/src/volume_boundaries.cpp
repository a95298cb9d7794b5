#include "volume_boundaries.h"

#include <algorithm>
#include <stdexcept>

namespace ladarsim::raytrace {
namespace {

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
void collect_crossing(const RTCFilterFunctionNArguments* args) {
    auto* context = reinterpret_cast<const CrossingContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        context->crossings->push_back({RTCHitN_geomID(args->hit, args->N, i), RTCHitN_primID(args->hit, args->N, i)});
        args->valid[i] = 0;
    }
}

}  // namespace

VolumeBoundaries::VolumeBoundaries(RTCDevice device, const Eigen::Vector3d& origin_world) : origin_world(origin_world) {
    volumes.reset(rtcNewScene(device));
    // Watertight triangle tests: a ray must not slip through the edge between two boundary
    // triangles and lose a crossing of a cloud. Volume boundaries are few: the care costs little.
    rtcSetSceneFlags(volumes.get(), RTC_SCENE_FLAG_ROBUST);
}

void VolumeBoundaries::add(const scene::SceneObject& object, Geometry g, const float* vertices) {
    rtcSetGeometryIntersectFilterFunction(g.get(), &collect_crossing);
    rtcCommitGeometry(g.get());
    const unsigned id = rtcAttachGeometry(volumes.get(), g.get());
    if (id != volume_objects.size()) throw std::logic_error("Embree geometry ids are not sequential");
    volume_objects.push_back(&object);
    volume_vertices.push_back(vertices);
    volume_geometries.push_back(std::move(g));
}

void VolumeBoundaries::commit() {
    rtcCommitScene(volumes.get());
    find_volumes_holding_origin();
}

/// The volume boundaries along a ray (origin relative to origin_world), nearest first, into
/// `boundaries` (reused: this runs per sub-ray in beams that meet a medium).
void VolumeBoundaries::boundaries_along(const Eigen::Vector3d& o, const Ray& ray, float time,
                                        std::vector<Boundary>& boundaries) const {
    thread_local std::vector<Crossing> crossings;
    crossings.clear();
    CrossingContext context;
    rtcInitIntersectContext(&context.context);
    context.crossings = &crossings;
    RTCRayHit rh;
    to_embree(ray, origin_world, time, rh);
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
void VolumeBoundaries::find_volumes_holding_origin() {
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
        boundaries_along(Eigen::Vector3d::Zero(), ray, 0.0f, boundaries);  // the volumes do not move: time 0
        for (const Boundary& b : boundaries) parity[b.geometry] ^= 1;
        for (std::size_t g = 0; g < parity.size(); ++g) votes[g] += parity[g];
    }
    for (std::size_t g = 0; g < votes.size(); ++g) origin_inside[g] = votes[g] >= 2;
}

std::vector<VolumeSegment> VolumeBoundaries::along(const Ray& ray, float time) const {
    std::vector<VolumeSegment> segments;
    along(ray, time, segments);
    return segments;
}

void VolumeBoundaries::along(const Ray& ray, float time, std::vector<VolumeSegment>& segments) const {
    segments.clear();
    if (volume_objects.empty()) return;
    const Eigen::Vector3d o = ray.origin_world - origin_world;
    auto close = [&](std::uint32_t geometry, double enter_m, double exit_m, std::uint32_t prim) {
        const scene::SceneObject& object = *volume_objects[geometry];
        const scene::Material& m = object.model->materials[object.model->mesh.triangle_material[prim]];
        segments.push_back({object.id, enter_m, exit_m, m.extinction_per_m, m.backscatter_per_m_sr});
    };
    struct Open { std::uint32_t geometry; double enter_m; std::uint32_t prim; };
    thread_local std::vector<Open> open;
    open.clear();
    const bool from_sensor = o.squaredNorm() < 1e-12;
    thread_local std::vector<Boundary> boundaries;
    boundaries_along(o, ray, time, boundaries);
    thread_local std::vector<std::uint32_t> met;  // volumes whose boundary this ray has crossed already
    met.clear();
    for (std::uint32_t g = 0; g < volume_objects.size(); ++g)
        if (from_sensor && origin_inside[g]) open.push_back({g, 0.0, 0});
    for (const Boundary& b : boundaries) {
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
}

}  // namespace ladarsim::raytrace
