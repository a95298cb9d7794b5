#pragma once
// Inside raytrace: an animated object's parts (each animation part of its model, and the triangles
// in none) in the top scene, as Embree user geometries. Embree's quaternion-blurred instances
// placed a part by slerping between time steps, and every time window paid Embree's rebuild of
// their motion bounds in the top scene (5.6 ms a frame for the default drone's four rotors, more
// than tracing the frame). Here the top scene holds only a box that contains each part over the
// window; a ray entering it is carried into the part's model frame at the ray's own time, by the
// animation itself rather than an interpolation of it, and traced against the part's BVH.
#include <cstdint>
#include <deque>
#include <limits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "embree_common.h"
#include "ladarsim/scene/animation.h"
#include "ladarsim/scene/scene.h"

namespace ladarsim::raytrace {

using Matrix34 = Eigen::Matrix<double, 3, 4>;

/// The affine map from an object's model coordinates to world - `origin_world` at `time_s`.
Matrix34 relative_from_model(const scene::SceneObject& object, const Eigen::Vector3d& origin_world, double time_s);

class AnimatedPart;

/// An animated object: its pose and its parts' motions at any time, and its parts' boxes over a window.
class AnimatedObject {
public:
    AnimatedObject(const scene::SceneObject& object, const Eigen::Vector3d& origin_world);

    /// Part `part`'s model coordinates (-1: the triangles in no part) -> world - origin at `time_s`.
    Matrix34 placement(int part, double time_s) const;

    /// The time of Embree's `u` (0 to 1) in the current window.
    double time_at(float u) const { return window_begin_s_ + window_length_s_ * static_cast<double>(u); }

    /// A part of this object: `part` an index into the model's animation parts, or -1 for its
    /// triangles in none; `bvh` those triangles in model coordinates, listed by `triangles` (the
    /// model's indices).
    AnimatedPart& add_part(int part, RTCScene bvh, const std::vector<std::uint32_t>& triangles);

    /// Sets the window [begin_s, begin_s + length_s] and bounds each part over it; commit their
    /// geometries after.
    void set_window(double begin_s, double length_s);

private:
    struct Posed {
        Matrix34 relative_from_model;
        std::vector<Eigen::Affine3d> motions;
    };
    void pose(double time_s, Posed& out) const;
    static Matrix34 part_of(const Posed& posed, int part);

    const scene::SceneObject* object_;
    scene::PartMotions motions_;
    Eigen::Vector3d origin_world_;
    double window_begin_s_ = 0.0, window_length_s_ = 0.0;
    std::deque<AnimatedPart> parts_;  // a deque: Embree and the top scene's entries point at them
};

class AnimatedPart {
public:
    /// Made by AnimatedObject::add_part.
    AnimatedPart(const AnimatedObject& object, int part, RTCScene bvh, const scene::TriangleMesh& mesh,
                 const std::vector<std::uint32_t>& triangles);
    AnimatedPart(const AnimatedPart&) = delete;
    AnimatedPart& operator=(const AnimatedPart&) = delete;

    /// The user geometry standing for this part; Embree keeps a pointer to the part.
    Geometry make_geometry(RTCDevice device) const;

    /// Model coordinates -> world - origin at Embree's time `u` of the current window.
    const Matrix34& relative_from_model_at(float u) const;

private:
    friend class AnimatedObject;
    struct Placement {
        double time_s = std::numeric_limits<double>::quiet_NaN();  // none yet
        Matrix34 relative_from_model;
        Eigen::Matrix3d model_from_relative_linear;
    };
    const Placement& placement(float u) const;
    // The box holding the part placed at `samples` (consecutive times of the window) and between.
    void bound(const std::vector<Matrix34>& samples);
    // The largest angle one of the part's box edges turns between consecutive samples.
    double largest_turn_rad(const std::vector<Matrix34>& samples) const;
    static void bounds(const RTCBoundsFunctionArguments* args);
    static void intersect(const RTCIntersectFunctionNArguments* args);

    const AnimatedObject* object_;
    int part_;
    RTCScene bvh_;
    Eigen::AlignedBox3d box_model_;  // the part's triangles at rest
    std::size_t serial_;             // this part's slot in each thread's cache of placements
    RTCBounds window_box_{};
};

}  // namespace ladarsim::raytrace
