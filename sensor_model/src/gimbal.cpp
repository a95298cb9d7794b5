#include "ladarsim/sensor_model/gimbal.h"

#include <algorithm>
#include <numbers>

namespace ladarsim::sensor_model {

namespace {
constexpr double kRad = std::numbers::pi / 180.0;

double step_towards(double from, double to, double max_step) {
    return from + std::clamp(to - from, -max_step, max_step);
}
}  // namespace

Gimbal::Gimbal(const SensorConfig& config, GimbalPointing start)
    : az_limit_rad_(config.gimbal_az_limit_deg * kRad),
      el_min_rad_(config.gimbal_el_min_deg * kRad),
      el_max_rad_(config.gimbal_el_max_deg * kRad),
      slew_rate_radps_(config.gimbal_slew_rate_dps * kRad),
      pointing_(clamp(start)) {}

GimbalPointing Gimbal::clamp(GimbalPointing target) const {
    return {std::clamp(target.az_rad, -az_limit_rad_, az_limit_rad_), std::clamp(target.el_rad, el_min_rad_, el_max_rad_)};
}

void Gimbal::slew_towards(GimbalPointing target, double duration_s) {
    // Azimuth does not wrap: the +-175 deg limit stops the gimbal from taking the short way round.
    const GimbalPointing goal = clamp(target);
    const double max_step = slew_rate_radps_ * duration_s;
    pointing_ = {step_towards(pointing_.az_rad, goal.az_rad, max_step),
                 step_towards(pointing_.el_rad, goal.el_rad, max_step)};
}

}  // namespace ladarsim::sensor_model
