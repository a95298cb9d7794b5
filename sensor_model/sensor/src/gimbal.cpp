#include "ladarsim/sensor_model/sensor/gimbal.h"

#include <algorithm>
#include <numbers>
#include "ladarsim/core/units.h"

namespace ladarsim::sensor_model {

namespace {

double step_towards(double from, double to, double max_step) {
    return from + std::clamp(to - from, -max_step, max_step);
}
}  // namespace

GimbalLimits GimbalLimits::read(JsonFields& g) {
    GimbalLimits x;
    x.az_limit_deg = g.number("az_limit_deg", 0.0, 180.0);
    x.el_min_deg = g.number("el_min_deg", -90.0, 90.0);
    x.el_max_deg = g.number("el_max_deg", -90.0, 90.0);
    x.slew_rate_dps = g.number("slew_rate_dps", 0.0, 1e4);
    if (x.el_min_deg > x.el_max_deg) g.fail("el_min_deg", "must not be above el_max_deg");
    return x;
}

nlohmann::json GimbalLimits::to_json() const {
    return {{"az_limit_deg", az_limit_deg}, {"el_min_deg", el_min_deg}, {"el_max_deg", el_max_deg}, {"slew_rate_dps", slew_rate_dps}};
}

Gimbal::Gimbal(const GimbalLimits& limits, GimbalPointing start)
    : az_limit_rad_(limits.az_limit_deg * kDeg),
      el_min_rad_(limits.el_min_deg * kDeg),
      el_max_rad_(limits.el_max_deg * kDeg),
      slew_rate_radps_(limits.slew_rate_dps * kDeg),
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
