#include "ladarsim/dataset/intensity_scale.h"

#include <algorithm>

#include "ladarsim/dataset/frame_pcd.h"

namespace ladarsim {

float largest_intensity(const std::vector<std::filesystem::path>& pcds,
                        const std::function<void(int done, int total)>& frame_scanned) {
    float largest = 0.0f;
    for (std::size_t i = 0; i < pcds.size(); ++i) {
        for (const Return& r : read_frame_pcd(pcds[i])) largest = std::max(largest, r.intensity);
        if (frame_scanned) frame_scanned(static_cast<int>(i + 1), static_cast<int>(pcds.size()));
    }
    return largest;
}

}  // namespace ladarsim
