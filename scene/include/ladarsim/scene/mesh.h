#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ladarsim::scene {

/// 1550 nm optical properties of a surface. Volume media (fog, cloud) arrive with the
/// sensor-physics issue.
struct Material {
    std::string name;
    /// Lambertian (diffuse) reflectance at the sensor wavelength, 0..1.
    double reflectance = 0.3;
};

/// Reflectance given to a glTF material that carries no `extras.ladar.reflectance`:
/// 0.3 sits in the middle of the 1550 nm estimates for vegetation, concrete and painted metal.
inline constexpr double kDefaultReflectance = 0.3;

/// Triangles in the model's own frame (metres), every one finite and non-degenerate.
struct TriangleMesh {
    std::vector<Eigen::Vector3f> positions;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    /// Index into Model::materials, one per triangle.
    std::vector<std::uint32_t> triangle_material;
};

/// A loaded model: the whole glTF node hierarchy flattened into one mesh in model coordinates.
struct Model {
    std::string source;  ///< file it came from, for messages
    TriangleMesh mesh;
    std::vector<Material> materials;

    Eigen::AlignedBox3f bounds() const;
};

}  // namespace ladarsim::scene
