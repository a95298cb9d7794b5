#pragma once
// Every point's neighbours within a radius, found for all the points at once.
#include <vector>

#include "ladarsim/detect/point_cloud.h"

namespace ladarsim::detect {

/// For each point, the indices of the points within `radius_m` of it (itself among them), in no
/// particular order, and with `squared_m2` their squared distances alike. FLANN's k-d tree as
/// PCL's KdTreeFLANN builds and searches it (the same neighbours), queried a block of points at a
/// time over TBB's threads: PCL's one query a call opened an OpenMP region each time, and such
/// searches took 65 % of `detect`'s time over dataset 3.
std::vector<std::vector<int>> neighbours_within(const Points& points, double radius_m,
                                                std::vector<std::vector<float>>* squared_m2 = nullptr);

}  // namespace ladarsim::detect
