#include "ladarsim/scene/mesh.h"

namespace ladarsim::scene {

Eigen::AlignedBox3f Model::bounds() const {
    Eigen::AlignedBox3f box;
    for (const auto& p : mesh.positions) box.extend(p);
    return box;
}

}  // namespace ladarsim::scene
