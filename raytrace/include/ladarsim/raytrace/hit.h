#pragma once
#include <cstdint>

#include <Eigen/Core>

#include "ladarsim/scene/object_class.h"

namespace ladarsim::raytrace {

/// A ray in world coordinates (double precision; recentred to float only inside raytrace/).
struct Ray {
    Eigen::Vector3d origin_world = Eigen::Vector3d::Zero();
    Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  ///< unit length
    double time_s = 0.0;                                   ///< emission time of the pulse it belongs to
    double max_range_m = 1e5;
};

/// What a ray hit. "No hit" is an empty std::optional<Hit>; Embree's sentinels never leave raytrace/.
struct Hit {
    double range_m = 0.0;            ///< distance from the ray origin, refined in double precision
    std::uint32_t object_id = 0;     ///< scene::kBackgroundObjectId for the background map
    scene::ObjectClass object_class = scene::ObjectClass::background;
    std::uint32_t material = 0;      ///< index into the object's Model::materials (0 for the map)
    float reflectance = 0.0f;        ///< diffuse reflectance at the sensor wavelength
    Eigen::Vector3f normal_world = Eigen::Vector3f::UnitZ();  ///< unit, facing the ray
    float cos_incidence = 1.0f;      ///< |cos| of the angle between the ray and the surface normal
};

/// A stretch of a ray inside a volume medium (fog, cloud).
struct VolumeSegment {
    std::uint32_t object_id = 0;
    double enter_m = 0.0;  ///< along the ray; 0 when the ray starts inside
    double exit_m = 0.0;   ///< the ray's max_range_m when it never leaves
    double extinction_per_m = 0.0;
    double backscatter_per_m_sr = 0.0;
};

}  // namespace ladarsim::raytrace
