#pragma once
// Rays aimed at points, and their closed-form distances to planes, for tests of the ray tracer.
#include <Eigen/Core>

#include "ladarsim/raytrace/hit.h"

namespace ladarsim::test {

inline raytrace::Ray ray_from(const Eigen::Vector3d& origin, const Eigen::Vector3d& towards, double time_s = 0.0) {
    raytrace::Ray r;
    r.origin_world = origin;
    r.direction = (towards - origin).normalized();
    r.time_s = time_s;
    return r;
}

/// Distance along a unit ray to the plane through `point` with normal `n`.
inline double plane_distance(const raytrace::Ray& r, const Eigen::Vector3d& point, const Eigen::Vector3d& n) {
    return (point - r.origin_world).dot(n) / r.direction.dot(n);
}

}  // namespace ladarsim::test
