#pragma once
// Units and angles, in one place: a quantity in degrees or milliradians times its unit is radians.
#include <numbers>

namespace ladarsim {

inline constexpr double kDeg = std::numbers::pi / 180.0;  ///< one degree in radians: angle_deg * kDeg
inline constexpr double kMrad = 1e-3;                     ///< one milliradian in radians: angle_mrad * kMrad

}  // namespace ladarsim
