#pragma once
// Per-frame comparison of a detected box with the ground-truth box (Algorithm 1's evaluation).
#include "ladarsim/dataset/frame.h"

namespace ladarsim::detect {

/// Euclidean distance between box centres, metres.
double centre_distance_m(const OrientedBox& a, const OrientedBox& b);

/// Intersection over union of the two boxes' volumes, treating both as axis-aligned in the
/// frame they are given in (orientation ignored). 0 when either box has no volume.
double axis_aligned_iou(const OrientedBox& a, const OrientedBox& b);

/// The same in bird's-eye view: of the boxes' footprints on the x-y plane (the sensor frame's z is
/// up), heights ignored. 0 when either footprint has no area.
double bev_iou(const OrientedBox& a, const OrientedBox& b);

/// A target's box from the box around its returns, knowing how a LADAR draws them: every return
/// lies on its beam's axis, and every beam whose footprint reaches the target can report it, so
/// the returns spread a footprint's width (`footprint_width_rad` x range) beyond the target across
/// the line of sight (projected on each axis of the frame). The centre is the returns' box's
/// (the spread is symmetric about the target); each extent is what remains of the returns' once
/// that spread is taken off, or `prior_size` where that is less: a 0.3 m drone at a kilometre is
/// narrower than the footprint, and its returns cannot give its size, only its place.
OrientedBox sensor_aware_box(const OrientedBox& points_box, double footprint_width_rad, const Eigen::Vector3d& prior_size);

}  // namespace ladarsim::detect
