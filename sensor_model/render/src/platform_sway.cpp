#include "ladarsim/sensor_model/render/platform_sway.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>

#include "ladarsim/core/units.h"
#include "ladarsim/scene/trajectory.h"

namespace ladarsim::sensor_model {

namespace {

// Bounds that only catch typos (degrees for radians, a period for a frequency).
constexpr double kMaxSwayAngle_deg = 45.0;
constexpr double kMaxSwayOffset_m = 100.0;
constexpr double kMaxSwayFrequency_hz = 1000.0;

}  // namespace

Eigen::Isometry3d PlatformSway::at(double time_s) const {
    double value[6] = {0, 0, 0, 0, 0, 0};
    for (const SwayComponent& c : components_)
        value[static_cast<int>(c.axis)] += c.amplitude * std::sin(2.0 * std::numbers::pi * c.frequency_hz * time_s + c.phase_rad);
    Eigen::Isometry3d m = Eigen::Isometry3d::Identity();
    m.translate(Eigen::Vector3d(value[3], value[4], value[5]));
    m.rotate(scene::orientation_from_ypr_deg(value[0] / kDeg, value[1] / kDeg, value[2] / kDeg));
    return m;
}

PlatformSway read_platform_sway(JsonFields& sway) {
    const auto seed = static_cast<std::uint64_t>(sway.integer("seed", 0, std::numeric_limits<long long>::max(), 1));
    // The phases drawn, in list order: 53 bits of each draw (mt19937_64's output is the same on
    // every platform, unlike the standard distributions').
    std::mt19937_64 draws(seed);
    const nlohmann::json& list = sway.array("components");
    if (list.empty()) sway.fail("components", "needs at least one component");
    std::vector<SwayComponent> components;
    for (std::size_t i = 0; i < list.size(); ++i) {
        JsonFields f(list[i], sway.file(), sway.path_of("components") + "[" + std::to_string(i) + "]");
        SwayComponent c;
        const std::string axis = f.choice("axis", {"yaw", "pitch", "roll", "x", "y", "z"}, "");
        if (axis.empty()) f.fail("axis", "required field is missing; one of: yaw, pitch, roll, x, y, z");
        const bool rotation = axis == "yaw" || axis == "pitch" || axis == "roll";
        c.axis = axis == "yaw" ? SwayComponent::Axis::yaw : axis == "pitch" ? SwayComponent::Axis::pitch
               : axis == "roll" ? SwayComponent::Axis::roll : axis == "x" ? SwayComponent::Axis::x
               : axis == "y" ? SwayComponent::Axis::y : SwayComponent::Axis::z;
        c.amplitude = rotation ? f.number("amplitude_deg", 0.0, kMaxSwayAngle_deg) * kDeg : f.number("amplitude_m", 0.0, kMaxSwayOffset_m);
        c.frequency_hz = f.number("frequency_hz", 0.0, kMaxSwayFrequency_hz);
        const double drawn = static_cast<double>(draws() >> 11) * 0x1.0p-53 * 2.0 * std::numbers::pi;
        c.phase_rad = f.has("phase_deg") ? f.number("phase_deg", -360.0, 360.0) * kDeg : drawn;
        f.reject_unknown_keys();
        components.push_back(c);
    }
    return PlatformSway(std::move(components));
}

}  // namespace ladarsim::sensor_model
