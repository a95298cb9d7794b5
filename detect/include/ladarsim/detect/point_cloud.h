#pragma once
// Frame points as detect/ sees them: positions in the sensor frame, and their intensities beside. Recorded frames
// and ladarsim's own read into the same thing.
#include <vector>

#include <Eigen/Core>

#include "ladarsim/dataset/frame.h"

namespace ladarsim::detect {

using Points = std::vector<Eigen::Vector3f>;

/// Positions of a frame's returns (sensor frame, metres).
Points positions_of(const std::vector<Return>& returns);

/// Intensities of a frame's returns (detected energy), in the order of positions_of.
std::vector<float> intensities_of(const std::vector<Return>& returns);

/// The axis-aligned box of some points, as an OrientedBox with identity orientation.
OrientedBox bounding_box(const Points& points);

}  // namespace ladarsim::detect
