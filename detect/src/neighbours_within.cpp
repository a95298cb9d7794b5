#include "neighbours_within.h"

#include <algorithm>

#include <flann/flann.hpp>
#include <tbb/parallel_for.h>

namespace ladarsim::detect {

std::vector<std::vector<int>> neighbours_within(const Points& points, double radius_m, std::vector<std::vector<float>>* squared_m2) {
    const std::size_t n = points.size();
    std::vector<std::vector<int>> found(n);
    std::vector<std::vector<float>> squared(n);
    if (n > 0) {
        static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "Points are packed x y z");
        // FLANN's matrices take float* but only read the points.
        float* xyz = const_cast<float*>(points.front().data());
        const flann::Matrix<float> all(xyz, n, 3);
        flann::Index<flann::L2_Simple<float>> tree(all, flann::KDTreeSingleIndexParams(15));
        tree.buildIndex();
        // PCL's search: FLANN's radius is squared, in float.
        const auto radius2 = static_cast<float>(radius_m * radius_m);
        constexpr std::size_t kBlock = 256;
        tbb::parallel_for(std::size_t{0}, (n + kBlock - 1) / kBlock, [&](std::size_t block) {
            const std::size_t first = block * kBlock, count = std::min(kBlock, n - first);
            std::vector<std::vector<int>> indices;
            std::vector<std::vector<float>> distances;
            flann::SearchParams search(-1, 0.0f, false);
            search.cores = 1;
            tree.radiusSearch(flann::Matrix<float>(xyz + 3 * first, count, 3), indices, distances, radius2, search);
            for (std::size_t j = 0; j < count; ++j) {
                found[first + j] = std::move(indices[j]);
                squared[first + j] = std::move(distances[j]);
            }
        });
    }
    if (squared_m2) *squared_m2 = std::move(squared);
    return found;
}

}  // namespace ladarsim::detect
