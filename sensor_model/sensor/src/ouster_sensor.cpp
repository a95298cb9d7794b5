#include "ladarsim/sensor_model/sensor/ouster_sensor.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <string_view>

#include "ladarsim/core/input_error.h"
#include "ladarsim/sensor_model/sensor/physical_constants.h"
#include "ladarsim/core/units.h"

namespace ladarsim::sensor_model {

namespace {


/// What Ouster's datasheets give per product line. OS1: 120 m at 80 % reflectance in 100 klx of
/// sunlight, beams of 0.13 deg FWHM (its 16- and 64-channel units; 32 channels are not listed).
/// OS2: 240 m; no divergence found, so an estimate: the OS1-128's 0.18 deg FWHM halved, as the OS2
/// spreads its 128 channels over half the OS1-128's vertical field (22.5 deg, not 45: the same
/// emitters behind twice the focal length).
/// Minimum range: the OS1 datasheet's range is 0.8 m - 120 m; none found for the OS2, so the
/// same 0.8 m (the same receiver design behind longer optics).
/// Peak power is not published: it is set so that the receiver estimated in ouster_sensor_json
/// sees an 80 % Lambertian target at the datasheet's range, in full daylight (ladarsim's
/// 0.25 W/m^2/nm of sunlight), at twice its threshold.
struct ProductLine {
    std::string_view prefix;
    double max_range_m;
    double min_range_m;
    double divergence_fwhm_deg;
    double peak_power_w;
};
constexpr ProductLine kProductLines[] = {{"OS-1", 120.0, 0.8, 0.13, 2.4}, {"OS-2", 240.0, 0.8, 0.09, 6.7}};

const ProductLine& product_line(const OusterCalibration& c) {
    for (const ProductLine& line : kProductLines) {
        if (c.product_line.starts_with(line.prefix)) return line;
    }
    throw InputError(c.metadata_file.string(), "prod_line", "\"" + c.product_line + "\": figures are known for OS-1 and OS-2 units only");
}

}  // namespace

nlohmann::json ouster_sensor_json(const OusterCalibration& c) {
    const ProductLine& line = product_line(c);
    const Eigen::Matrix3d rotation = c.lidar_to_sensor.topLeftCorner<3, 3>();
    if ((rotation.col(2) - Eigen::Vector3d::UnitZ()).norm() > 1e-6) {
        throw InputError(c.metadata_file.string(), "lidar_to_sensor_transform", "tilts the lidar's axis; a channel_table head turns about z only");
    }
    // Column k fires at encoder angle 360 (1 - k / columns) deg, turned by the transform's yaw.
    const double first_column_azimuth_deg = std::remainder(std::atan2(rotation(1, 0), rotation(0, 0)) / kDeg, 360.0);
    std::vector<double> azimuth_offset_deg;
    for (double a : c.beam_azimuth_deg) azimuth_offset_deg.push_back(-a);  // Ouster's azimuths turn clockwise
    std::string name = "ouster_" + c.product_line;
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });

    // Every channel has its own emitter, firing once a column: a beam sees one pulse.
    const double pulse_rate_hz = c.columns_per_frame * c.frame_rate_hz;
    // The datasheets' false positive rate, one point in 10,000 pixels, as noise crossings per
    // second of listening: each pixel listens for the time of flight to the unit's range.
    const double false_alarm_rate_hz = 1e-4 / (2.0 * line.max_range_m / kSpeedOfLight_mps);
    // Gaussian beam: full angle at 1/e^2 irradiance = FWHM x 2 / sqrt(2 ln 2).
    const double divergence_mrad = line.divergence_fwhm_deg * kDeg * 1e3 * 2.0 / std::sqrt(2.0 * std::numbers::ln2);
    // Ouster publishes no radiometry. What follows are estimates for an 865 nm VCSEL emitter and a
    // SPAD-array receiver, written with the keys of ladarsim's APD receiver: a pixel of ~10 % photon
    // detection efficiency, high gain and little excess noise, about a million dark counts a second,
    // looking through a ~30 mm lens at as wide a field as its beam (the three models share one housing).
    const double pulse_width_ns = 4.0;
    const double photon_detection_efficiency = 0.1;
    const double wavelength_nm = 865.0;
    return {
        {"name", name},
        {"description", "Ouster " + c.product_line + " " + c.serial + " (firmware " + c.firmware + ") made from " +
                            c.metadata_file.filename().string() + " by ladarsim; radiometry is an estimate"},
        {"scan",
         {{"pattern", "channel_table"},
          {"frame_rate_hz", c.frame_rate_hz},
          {"columns", c.columns_per_frame},
          {"first_column_azimuth_deg", first_column_azimuth_deg},
          {"elevation_deg", c.beam_altitude_deg},
          {"azimuth_offset_deg", azimuth_offset_deg}}},
        {"transmitter",
         {{"wavelength_nm", wavelength_nm},
          {"peak_power_w", line.peak_power_w},
          {"pulse_width_ns", pulse_width_ns},
          {"pulse_rate_hz", pulse_rate_hz},
          {"divergence_mrad", divergence_mrad},
          {"divergence_el_mrad", divergence_mrad}}},
        {"optics",
         {{"aperture_diameter_m", 0.03}, {"optics_efficiency", 0.5}, {"receiver_fov_mrad", divergence_mrad}, {"filter_width_nm", 10.0}}},
        {"receiver",
         {{"responsivity_a_per_w", photon_detection_efficiency * kElementaryCharge_c * wavelength_nm * 1e-9 / (kPlanck_j_s * kSpeedOfLight_mps)},
          {"apd_gain", 1000.0},
          {"excess_noise_factor", 1.5},
          {"bandwidth_hz", 1.0 / (pulse_width_ns * 1e-9)},
          {"dark_current_a", 1e6 * kElementaryCharge_c},
          {"load_resistance_ohm", 10e3},
          {"temperature_k", 300.0},
          {"saturation_current_a", 2e-3},
          {"false_alarm_rate_hz", false_alarm_rate_hz},
          {"max_range_m", line.max_range_m},
          {"min_range_m", line.min_range_m},
          {"range_folding", false},
          // Surfaces closer along a beam than half a pulse length make one echo.
          {"return_gap_m", kSpeedOfLight_mps * pulse_width_ns * 1e-9 / 2.0},
          // The datasheets: one return per pixel, the strongest.
          {"reported_returns", "strongest"}}},
        {"gimbal", {{"az_limit_deg", 0.0}, {"el_min_deg", 0.0}, {"el_max_deg", 0.0}, {"slew_rate_dps", 0.0}}},
    };
}

}  // namespace ladarsim::sensor_model
