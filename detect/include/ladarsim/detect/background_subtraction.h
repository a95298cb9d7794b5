#pragma once
// Step 1 of Algorithm 1: remove what the initial map already holds.
#include <memory>

#include "ladarsim/detect/point_cloud.h"

namespace ladarsim::detect {

/// An octree of the initial map, built once; a frame point survives when its voxel holds no map
/// point. This is what PCL's OctreePointCloudChangeDetector reports for the current buffer against
/// the map, without rebuilding the map's octree every frame (detection.md); a point outside the
/// map's bounding box is new by definition.
class BackgroundSubtractor {
public:
    BackgroundSubtractor(const Points& map, double resolution_m);
    ~BackgroundSubtractor();
    BackgroundSubtractor(const BackgroundSubtractor&) = delete;
    BackgroundSubtractor& operator=(const BackgroundSubtractor&) = delete;

    Points subtract(const Points& frame) const;
    double resolution_m() const { return resolution_; }

private:
    struct Octree;
    std::unique_ptr<Octree> octree_;
    double resolution_;
};

}  // namespace ladarsim::detect
