#pragma once
#include <filesystem>

#include "ladarsim/scene/mesh.h"

namespace ladarsim::scene {

/// Writes a model as glTF 2.0: binary `.glb` when the file ends in .glb, else `.gltf` with the
/// buffer embedded as base64. One node, one primitive per material, each material's reflectance in
/// `extras.ladar.reflectance` so that load_gltf gives the model back. Model coordinates (x forward,
/// y left, z up) are mapped to glTF's (x, y, z) = (y, z, x), the inverse of load_gltf's mapping.
/// Written to a temporary name and renamed when complete; throws InputError naming the file.
void write_gltf(const Model& model, const std::filesystem::path& file);

}  // namespace ladarsim::scene
