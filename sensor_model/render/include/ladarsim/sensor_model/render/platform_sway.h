#pragma once
// The sway of a sensor's platform (a ship's roll, a mast in the wind): a sum of sinusoids about
// and along the platform's own axes (docs/scenario.md, "A moving platform").
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "ladarsim/core/json_fields.h"

namespace ladarsim::sensor_model {

struct SwayComponent {
    /// Rotations as the scene's yaw, pitch and roll; translations along the platform's x (forward),
    /// y (left) and z (up).
    enum class Axis { yaw, pitch, roll, x, y, z };
    Axis axis = Axis::yaw;
    double amplitude = 0.0;  ///< radians about yaw, pitch, roll; metres along x, y, z
    double frequency_hz = 0.0;
    double phase_rad = 0.0;
};

class PlatformSway {
public:
    PlatformSway() = default;
    explicit PlatformSway(std::vector<SwayComponent> components) : components_(std::move(components)) {}

    bool empty() const { return components_.empty(); }
    const std::vector<SwayComponent>& components() const { return components_; }
    /// platform_from_swayed at `time_s`: each axis' sum of amplitude * sin(2 pi f t + phase), the
    /// translation applied after the rotation (yaw, then pitch, then roll).
    Eigen::Isometry3d at(double time_s) const;

private:
    std::vector<SwayComponent> components_;
};

/// A "sway" object: "components", each {"axis", "amplitude_deg" (yaw, pitch, roll) or
/// "amplitude_m" (x, y, z), "frequency_hz", "phase_deg" (optional)}, and "seed" (optional, default
/// 1): a component without a phase draws it, uniform over the circle, from the seed and its place
/// in the list, so that a sway is the same in every run of its scenario. Throws InputError naming
/// the field.
PlatformSway read_platform_sway(JsonFields& sway);

}  // namespace ladarsim::sensor_model
