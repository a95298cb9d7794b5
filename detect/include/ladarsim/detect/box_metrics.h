#pragma once
// Per-frame comparison of a detected box with the ground-truth box (Algorithm 1's evaluation).
#include "ladarsim/dataset/frame.h"

namespace ladarsim::detect {

/// Euclidean distance between box centres, metres.
double centre_distance_m(const OrientedBox& a, const OrientedBox& b);

/// Intersection over union of the two boxes' volumes, treating both as axis-aligned in the
/// frame they are given in (orientation ignored). 0 when either box has no volume.
double axis_aligned_iou(const OrientedBox& a, const OrientedBox& b);

}  // namespace ladarsim::detect
