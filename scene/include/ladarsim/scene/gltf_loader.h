#pragma once
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "ladarsim/scene/mesh.h"

namespace ladarsim::scene {

/// What loading cleaned up, for the log and for tests.
struct GltfLoadReport {
    std::size_t triangles_loaded = 0;
    std::size_t degenerate_dropped = 0;  ///< zero-area or repeated-index triangles
    std::size_t nonfinite_dropped = 0;   ///< triangles touching a NaN/inf vertex
    std::vector<std::string> defaulted_materials;  ///< materials without extras.ladar.reflectance
};

/// Loads a glTF 2.0 file (.gltf with external or embedded buffers, or .glb): every triangle
/// primitive of every node of the default scene (or all root nodes if none is set), node
/// transforms composed down the hierarchy, flattened into one mesh in ladarsim's model frame.
///
/// Model frame: x forward, y left, z up. glTF is y up with the asset's front along +z, so a glTF
/// point (x, y, z) becomes (z, x, y) here (a proper rotation: handedness is kept).
///
/// Material reflectance comes from the material's `extras.ladar.reflectance`; a material
/// without it gets kDefaultReflectance and a warning naming it. Throws InputError naming the file
/// and the glTF field for anything malformed.
Model load_gltf(const std::filesystem::path& file, GltfLoadReport* report = nullptr);

}  // namespace ladarsim::scene
