#pragma once
// Step 1 of Algorithm 1: remove what the initial map already holds.
#include <memory>

#include "ladarsim/detect/point_cloud.h"

namespace ladarsim::detect {

/// The map's occupied voxels, found once and dilated by one voxel; a frame point survives when its
/// voxel is not among them (so no map point lies within one voxel of it). PCL's
/// OctreePointCloudChangeDetector compares a frame with a rebuilt buffer every time and tests only
/// the point's own voxel, which lets a static surface through wherever its noisy returns straddle a
/// voxel boundary (2.5 % of a wall's points for 5 cm of noise in 1 m voxels); an octree radius
/// search fixes that but costs 2.5 us a point against a 1 M-point map. A hash of dilated voxel keys
/// answers in one lookup (benchmarks/detect_speed).
///
/// A point also goes when the map lies within `range_tolerance_m` of it along its own line of
/// sight: the initial map is surveyed with single rays, while a frame's footprint grazing distant
/// ground reports the range where its stretched pulse crosses the threshold, metres nearer or
/// farther than its axis' hit (dataset 1 over Autzen: ~100 ground returns a frame 0.5-2 m along
/// the line of sight from the surveyed voxels, each a false track for a tracker of every target).
class BackgroundSubtractor {
public:
    BackgroundSubtractor(const Points& map, double resolution_m, double range_tolerance_m = 0.0);
    ~BackgroundSubtractor();
    BackgroundSubtractor(const BackgroundSubtractor&) = delete;
    BackgroundSubtractor& operator=(const BackgroundSubtractor&) = delete;

    Points subtract(const Points& frame) const;
    double resolution_m() const { return resolution_; }

private:
    struct VoxelSet;
    std::unique_ptr<VoxelSet> voxels_;
    double resolution_, range_tolerance_;
};

}  // namespace ladarsim::detect
