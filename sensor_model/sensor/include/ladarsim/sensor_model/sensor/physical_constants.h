#pragma once
// CODATA 2018 exact values (SI 2019 definitions).
namespace ladarsim::sensor_model {

inline constexpr double kSpeedOfLight_mps = 299'792'458.0;
inline constexpr double kElementaryCharge_c = 1.602'176'634e-19;
inline constexpr double kBoltzmann_j_per_k = 1.380'649e-23;
inline constexpr double kPlanck_j_s = 6.626'070'15e-34;

}  // namespace ladarsim::sensor_model
