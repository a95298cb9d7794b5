#pragma once
// Inside raytrace only (Embree types never leave it): what the top scene of TracedScene and its
// volume boundaries share about Embree: owning handles, our rays in Embree's form, and the
// distance to a triangle Embree reported, redone in double precision.
#include <cmath>
#include <memory>
#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <embree3/rtcore.h>

#include "ladarsim/raytrace/hit.h"

namespace ladarsim::raytrace {

// Owning handles: Embree objects are reference counted C handles.
struct DeviceDeleter { void operator()(RTCDeviceTy* d) const { rtcReleaseDevice(d); } };
struct SceneDeleter { void operator()(RTCSceneTy* s) const { rtcReleaseScene(s); } };
struct GeometryDeleter { void operator()(RTCGeometryTy* g) const { rtcReleaseGeometry(g); } };
using Device = std::unique_ptr<RTCDeviceTy, DeviceDeleter>;
using EmbreeScene = std::unique_ptr<RTCSceneTy, SceneDeleter>;
using Geometry = std::unique_ptr<RTCGeometryTy, GeometryDeleter>;

// Ray-triangle distance in double precision (Moller-Trumbore). Embree's float t carries a relative
// error of a few 1e-7, i.e. millimetres at 2 km; the vertices it tested are exact floats, so
// repeating the intersection in double recovers the range to well below a millimetre.
inline std::optional<double> triangle_distance(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& a,
                                               const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const Eigen::Vector3d e1 = b - a, e2 = c - a;
    const Eigen::Vector3d p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-300) return std::nullopt;
    const Eigen::Vector3d s = o - a;
    return e2.dot(s.cross(e1)) / det;
}

// `ray` for Embree, its origin relative to `origin_world` and `time` its place in the time window
// (0 to 1) that the motion-blurred instances span.
inline void to_embree(const Ray& ray, const Eigen::Vector3d& origin_world, float time, RTCRayHit& rh) {
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
    rh.ray.time = time;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

}  // namespace ladarsim::raytrace
