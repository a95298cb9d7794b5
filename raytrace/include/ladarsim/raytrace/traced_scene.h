#pragma once
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "ladarsim/raytrace/hit.h"
#include "ladarsim/scene/scene.h"

namespace ladarsim::raytrace {

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

    std::optional<Hit> trace(const Ray& ray) const;
    /// Traces many rays at once (Embree streams); results[i] belongs to rays[i].
    void trace(std::span<const Ray> rays, std::span<std::optional<Hit>> results) const;

    /// Where the ray runs inside volume media, up to its max_range_m, in order of entry. Volumes are
    /// placed where their trajectory puts them at time 0 (clouds drift little over a scan). Meshes
    /// must be closed and face outwards: a ray that first meets a back face started inside.
    std::vector<VolumeSegment> volumes_along(const Ray& ray) const;
    bool has_volumes() const;

    const Eigen::Vector3d& origin_world() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace ladarsim::raytrace
