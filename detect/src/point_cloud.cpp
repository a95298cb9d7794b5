#include "ladarsim/detect/point_cloud.h"

#include <Eigen/Geometry>

namespace ladarsim::detect {

Points positions_of(const std::vector<Return>& returns) {
    Points p;
    p.reserve(returns.size());
    for (const auto& r : returns) p.push_back(r.position_sensor);
    return p;
}

std::vector<float> intensities_of(const std::vector<Return>& returns) {
    std::vector<float> v;
    v.reserve(returns.size());
    for (const auto& r : returns) v.push_back(r.intensity);
    return v;
}

OrientedBox bounding_box(const Points& points) {
    Eigen::AlignedBox3f box;
    for (const auto& p : points) box.extend(p);
    OrientedBox b;
    if (box.isEmpty()) return b;
    b.centre = box.center().cast<double>();
    b.size = box.sizes().cast<double>();
    return b;
}

}  // namespace ladarsim::detect
