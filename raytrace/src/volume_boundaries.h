#pragma once
// Inside raytrace only: the boundaries of a scene's volume media (fog, cloud) in an Embree scene of
// their own, which rays pass through, and where a ray runs inside each medium.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "embree_common.h"
#include "ladarsim/raytrace/hit.h"
#include "ladarsim/scene/scene.h"

namespace ladarsim::raytrace {

class VolumeBoundaries {
public:
    /// No volumes yet, on `device`; rays reach Embree relative to `origin_world`, where every beam starts.
    VolumeBoundaries(RTCDevice device, const Eigen::Vector3d& origin_world);

    /// Adds a volume object's closed, outward-facing mesh: `g` holds its triangles relative to
    /// origin_world (not yet committed), `vertices` is Embree's vertex buffer of them.
    void add(const scene::SceneObject& object, Geometry g, const float* vertices);
    /// Builds the BVH once every volume is added, and decides which volumes hold the origin.
    void commit();

    bool empty() const { return volume_objects.empty(); }
    /// TracedScene::volumes_along for a ray at `time` in the scene's time window (0 to 1).
    std::vector<VolumeSegment> along(const Ray& ray, float time) const;
    /// The same into `segments` (cleared first; per-thread scratch inside: no allocation once warm).
    void along(const Ray& ray, float time, std::vector<VolumeSegment>& segments) const;

private:
    struct Boundary {
        double range_m;  // in double, from the triangle itself
        bool entering;
        std::uint32_t geometry, prim;
    };
    void boundaries_along(const Eigen::Vector3d& o, const Ray& ray, float time, std::vector<Boundary>& boundaries) const;
    void find_volumes_holding_origin();

    Eigen::Vector3d origin_world;
    EmbreeScene volumes;  // fog and cloud boundaries, traced only by volumes_along
    std::vector<const scene::SceneObject*> volume_objects;  // by geometry id in `volumes`
    std::vector<const float*> volume_vertices;
    std::vector<Geometry> volume_geometries;
    std::vector<bool> origin_inside;  // by geometry id: the volume holds origin_world
};

}  // namespace ladarsim::raytrace
