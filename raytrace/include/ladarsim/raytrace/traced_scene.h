#pragma once
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ladarsim/raytrace/hit.h"
#include "ladarsim/scene/scene.h"

namespace ladarsim::raytrace {

/// Where an object's mesh is for a ray of a given time: its model-space box, the affine map Embree
/// applies to it then, and a sphere holding it.
struct ObjectBounds {
    std::uint32_t object_id = 0;
    Eigen::AlignedBox3d box_model;
    Eigen::Matrix<double, 3, 4> world_from_model = Eigen::Matrix<double, 3, 4>::Identity();
    Eigen::Vector3d centre_world = Eigen::Vector3d::Zero();
    double radius_m = 0.0;
    bool moving = false;  ///< traced with motion blur
    bool volume = false;  ///< a medium (fog, cloud), seen only by volumes_along()
};

/// A scene.Scene inside Embree. Each object's mesh becomes one BVH, built once; each object is an
/// instance of it, with Embree motion-blur time steps when its trajectory moves, so that a ray
/// carries its own emission time. The background map is a set of oriented discs in the top scene.
/// Objects whose materials are all volume media (fog, cloud) live in a scene of their own: rays
/// pass through them, and volumes_along() says where.
///
/// Coordinates: everything handed to Embree is single precision relative to `origin_world`
/// (choose the sensor position): large geo-referenced coordinates never reach float.
class TracedScene {
public:
    TracedScene(const scene::Scene& scene, const Eigen::Vector3d& origin_world);
    ~TracedScene();
    TracedScene(const TracedScene&) = delete;
    TracedScene& operator=(const TracedScene&) = delete;

    /// Places every moving instance for rays emitted in [begin_s, end_s] (a frame), sampling each
    /// trajectory at `motion_steps` >= 2 evenly spaced times (Embree interpolates linearly between).
    /// Must be called before tracing, and again for each new time window.
    void set_time_window(double begin_s, double end_s, int motion_steps);
    /// Where the rays of this time window leave (object_bounds_near's cones): within `radius_m` of
    /// `centre_world`, a sensor on a moving platform over a frame. Until called, origin_world()
    /// exactly. Call after set_time_window, for each window.
    void set_viewpoint(const Eigen::Vector3d& centre_world, double radius_m);

    std::optional<Hit> trace(const Ray& ray) const;
    /// Traces many rays at once (Embree streams); results[i] belongs to rays[i].
    void trace(std::span<const Ray> rays, std::span<std::optional<Hit>> results) const;
    /// The same against the static geometry only (static meshes and the background map), whatever
    /// the time window: for rays that stand for many beams fired at other times.
    void trace_static(std::span<const Ray> rays, std::span<std::optional<Hit>> results) const;

    /// Where the ray runs inside volume media, up to its max_range_m, in order of entry. Volumes are
    /// placed where their trajectory puts them at time 0 (clouds drift little over a scan). Meshes
    /// must be closed and face outwards: a ray that first meets a back face started inside.
    std::vector<VolumeSegment> volumes_along(const Ray& ray) const;
    /// The same into `segments` (cleared first), allocating nothing once it is warm.
    void volumes_along(const Ray& ray, std::vector<VolumeSegment>& segments) const;
    bool has_volumes() const;

    /// The bounds of every mesh object (not the background map) for a ray emitted at `time_s`: a
    /// moving object's transform is the same linear interpolation between motion steps that Embree
    /// applies (it can only shrink the mesh, never grow it, so the sphere still holds it). Fills
    /// `out` in the scene's object order.
    void object_bounds(double time_s, std::vector<ObjectBounds>& out) const;

    /// object_bounds() of only those objects that a cone from the viewpoint can meet: the ones
    /// whose sphere over the whole time window (holding the object at every time in it), its
    /// angular radius beta scaled by `radius_factor`, comes within `half_angle_rad` of `axis_world`
    /// (a unit vector): angle(axis, centre) <= half_angle_rad + radius_factor * beta. Each object's
    /// window sphere is found once per time window, so that a beam tests one dot product per
    /// object instead of placing and testing every object. Static meshes whose sphere subtends
    /// `static_wider_rad` or more from the viewpoint (asin(radius / distance); pi / 2 when it
    /// holds it) are left out too. A viewpoint of radius r tests every window sphere grown by r:
    /// a cone from anywhere within r of its centre meets no object the test leaves out. Fills
    /// `out` in the scene's object order.
    void object_bounds_near(const Eigen::Vector3d& axis_world, double half_angle_rad, double radius_factor, double time_s,
                            double static_wider_rad, std::vector<ObjectBounds>& out) const;

    const Eigen::Vector3d& origin_world() const;

    /// For benchmarks: from now on every traced batch of rays is appended to `log` (null: stop).
    void record_rays(std::vector<std::vector<Ray>>* log);
    /// For benchmarks: Embree's traversal alone on this scene, as trace() calls it but without
    /// making hit records. Returns the number of hits.
    std::size_t intersect_only(std::span<const Ray> rays) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace ladarsim::raytrace
