#include "ladarsim/detect/background_subtraction.h"

#include <stdexcept>

#include <pcl/octree/octree_search.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace ladarsim::detect {

struct BackgroundSubtractor::Octree {
    pcl::PointCloud<pcl::PointXYZ>::Ptr cloud{new pcl::PointCloud<pcl::PointXYZ>};
    pcl::octree::OctreePointCloudSearch<pcl::PointXYZ> tree;
    explicit Octree(double resolution) : tree(resolution) {}
};

BackgroundSubtractor::BackgroundSubtractor(const Points& map, double resolution_m) : resolution_(resolution_m) {
    if (!(resolution_m > 0.0)) throw std::invalid_argument("background subtraction resolution must be positive");
    octree_ = std::make_unique<Octree>(resolution_m);
    for (const auto& p : map) octree_->cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
    if (!octree_->cloud->empty()) {
        octree_->tree.setInputCloud(octree_->cloud);
        octree_->tree.addPointsFromInputCloud();
    }
}

BackgroundSubtractor::~BackgroundSubtractor() = default;

Points BackgroundSubtractor::subtract(const Points& frame) const {
    if (octree_->cloud->empty()) return frame;
    double min_x, min_y, min_z, max_x, max_y, max_z;
    octree_->tree.getBoundingBox(min_x, min_y, min_z, max_x, max_y, max_z);
    Points kept;
    for (const auto& p : frame) {
        const bool inside = p.x() >= min_x && p.x() <= max_x && p.y() >= min_y && p.y() <= max_y && p.z() >= min_z &&
                            p.z() <= max_z;
        if (!inside || !octree_->tree.isVoxelOccupiedAtPoint(pcl::PointXYZ(p.x(), p.y(), p.z()))) kept.push_back(p);
    }
    return kept;
}

}  // namespace ladarsim::detect
