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

Eigen::AlignedBox3d bounds_of(const TriangleMesh& mesh, const std::vector<std::uint32_t>& triangles) {
    Eigen::AlignedBox3d box;
    for (const std::uint32_t t : triangles)
        for (const std::uint32_t v : mesh.triangles[t]) box.extend(mesh.positions[v].cast<double>());
    return box;
}

}  // namespace ladarsim::scene
