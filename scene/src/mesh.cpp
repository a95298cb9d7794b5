#include "ladarsim/scene/mesh.h"

#include <algorithm>

namespace ladarsim::scene {

Eigen::AlignedBox3f Model::bounds() const {
    Eigen::AlignedBox3f box;
    for (const auto& p : mesh.positions) box.extend(p);
    return box;
}

bool Model::is_volume() const {
    return !materials.empty() && std::all_of(materials.begin(), materials.end(), [](const Material& m) { return m.is_volume(); });
}

}  // namespace ladarsim::scene
