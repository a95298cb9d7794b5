#pragma once
#include "ladarsim/sensor_model/sensor_config.h"

namespace ladarsim::sensor_model {

/// Pointing of the field centre in the sensor (mount) frame.
struct GimbalPointing {
    double az_rad = 0.0;  ///< about +z, positive to the left
    double el_rad = 0.0;  ///< positive up
};

/// A two-axis gimbal: each axis turns at up to the slew rate, within its limits. It is held still
/// while a frame is scanned (step and stare) and moves between frames.
class Gimbal {
public:
    Gimbal(const SensorConfig& config, GimbalPointing start);

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
