#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ladarsim::scene {

/// Optical properties at the sensor wavelength. A material with extinction is a volume medium
/// (fog, cloud): its closed mesh bounds a region that attenuates and backscatters, and is never a
/// reflecting surface.
struct Material {
    std::string name;
    /// Lambertian (diffuse) reflectance at the sensor wavelength, 0..1.
    double reflectance = 0.3;
    double extinction_per_m = 0.0;      ///< > 0 makes this a volume medium
    double backscatter_per_m_sr = 0.0;  ///< volume backscatter coefficient (180 deg)

    bool is_volume() const { return extinction_per_m > 0.0; }
};

/// Fog of meteorological optical range `mor_m` (Hahner et al. 2021): extinction ln(20) / MOR,
/// backscatter 0.046 / MOR.
inline Material fog_medium(std::string name, double mor_m) {
    return Material{std::move(name), 0.0, 2.995732273553991 / mor_m, 0.046 / mor_m};
}

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

/// The box at rest (model frame) of the mesh's `triangles` (indices into mesh.triangles): what an
/// animation part's placements move.
Eigen::AlignedBox3d bounds_of(const TriangleMesh& mesh, const std::vector<std::uint32_t>& triangles);

struct Animation;

/// A loaded model: the whole glTF node hierarchy flattened into one mesh in model coordinates.
struct Model {
    std::string source;  ///< file it came from, for messages
    TriangleMesh mesh;
    std::vector<Material> materials;
    /// The glTF file's node animations (animation.h), null when it has none. The mesh above is
    /// the model at rest.
    std::shared_ptr<const Animation> animation;

    /// The mesh at rest.
    Eigen::AlignedBox3f bounds() const;
    /// True when every material is a volume medium: the model is a fog or cloud volume.
    bool is_volume() const;
};

}  // namespace ladarsim::scene
