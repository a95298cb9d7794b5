#pragma once
// The probes that speak for a patch of a footprint (plane or curved), weighted by the beam's
// irradiance where each points.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "ladarsim/sensor_model/footprint/beam.h"
#include "ladarsim/sensor_model/footprint/footprint.h"

namespace ladarsim::sensor_model {

struct PatchProbes {
    std::vector<const Probe*> used;  ///< inside the truncation (not sentinels), outside the excluded part
    std::vector<double> gauss;       ///< the irradiance of each of them that met something
    int hits = 0;
    bool one_object = true;          ///< every hit on one object
    std::uint32_t object_id = 0;     ///< the first hit's
    Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero(), point_sum = Eigen::Vector3d::Zero();
    double reflectance_sum = 0.0, g_sum = 0.0;

    /// Starts again from `probes`, those inside `footprint`'s truncation and outside `excluded`.
    void gather(const Footprint& footprint, std::span<const Probe> probes, const std::optional<FootprintRect>& excluded);
    /// Every probe met something, all one object.
    bool one_surface_met() const { return !used.empty() && hits == static_cast<int>(used.size()) && one_object; }
};

}  // namespace ladarsim::sensor_model
