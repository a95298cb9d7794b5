#pragma once
#include <nlohmann/json.hpp>

#include "ladarsim/core/json_fields.h"

namespace ladarsim::sensor_model {

/// Pointing of the field centre in the sensor (mount) frame.
struct GimbalPointing {
    double az_rad = 0.0;  ///< about +z, positive to the left
    double el_rad = 0.0;  ///< positive up
};

/// How far and how fast the mount can turn the field. A fixed head (a spinning lidar) has all four zero
/// (elevation limits both 0).
struct GimbalLimits {
    double az_limit_deg = 0.0;   ///< +- about the mount's z axis
    double el_min_deg = 0.0;
    double el_max_deg = 0.0;
    double slew_rate_dps = 0.0;

    /// Throws InputError naming the key (el_min_deg must not lie above el_max_deg).
    static GimbalLimits read(JsonFields& gimbal);
    nlohmann::json to_json() const;
};

/// A two-axis gimbal: each axis turns at up to the slew rate, within its limits. It is held still
/// while a frame is scanned (step and stare) and moves between frames.
class Gimbal {
public:
    Gimbal(const GimbalLimits& limits, GimbalPointing start);

    GimbalPointing pointing() const { return pointing_; }
    /// Turns for `duration_s` towards `target` (clamped to the limits), each axis at most
    /// slew rate * duration.
    void slew_towards(GimbalPointing target, double duration_s);
    /// `target` clamped to the gimbal's limits.
    GimbalPointing clamp(GimbalPointing target) const;

private:
    double az_limit_rad_, el_min_rad_, el_max_rad_, slew_rate_radps_;
    GimbalPointing pointing_;
};

}  // namespace ladarsim::sensor_model
