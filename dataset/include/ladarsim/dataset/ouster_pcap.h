#pragma once
// Recorded frames from a real Ouster lidar: its metadata (the unit's own calibration), its lidar
// packets in a libpcap capture decoded into the frame format.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "ladarsim/dataset/frame.h"

namespace ladarsim {

/// What a unit's metadata file says about its lidar, in Ouster's own conventions.
struct OusterCalibration {
    std::filesystem::path metadata_file;  ///< where it was read (named by errors and descriptions)
    std::string product_line;             ///< prod_line, e.g. "OS-1-32-G"
    std::string serial;                   ///< prod_sn
    std::string firmware;                 ///< build_rev
    int columns_per_frame = 0;
    int pixels_per_column = 0;            ///< channels
    int columns_per_packet = 0;
    double frame_rate_hz = 0.0;           ///< from lidar_mode ("1024x10": 10 Hz)
    /// One per channel, channel 0 (the top) first; degrees. Azimuths in Ouster's sense: positive
    /// turns the beam clockwise seen from above (it fires later in the revolution's angle).
    std::vector<double> beam_altitude_deg;
    std::vector<double> beam_azimuth_deg;
    double lidar_origin_to_beam_origin_mm = 0.0;
    Eigen::Matrix4d lidar_to_sensor = Eigen::Matrix4d::Identity();  ///< translation in mm
    std::vector<int> pixel_shift_by_row;  ///< Ouster's destaggering shifts, columns
    std::array<int, 2> column_window{};   ///< first and last measurement_id the unit sends
    std::string udp_profile_lidar = "LEGACY";  ///< packet layout ("LEGACY" when the metadata names none)
    int udp_port_lidar = 7502;
};

/// Reads an Ouster metadata file: the flat layout of firmware up to 2.3 (calibration at the top
/// level, packet format under "data_format") or the sectioned one of 2.4 and later
/// ("beam_intrinsics", "lidar_data_format", ...). Throws InputError naming the file and the field
/// for a field that is missing, mistyped or inconsistent with the others.
OusterCalibration read_ouster_metadata(const std::filesystem::path& file);

/// Decodes the lidar packets (LEGACY or RNG19_RFL8_SIG16_NIR16 profile, UDP port of the
/// calibration) of a pcap capture into frames, one per frame_id. Every pixel of a valid column
/// with a range becomes a Return: position by Ouster's range-to-xyz formula (encoder angle from
/// measurement_id, the beam's azimuth and altitude, the beam origin's offset from the axis)
/// turned by the rotation of lidar_to_sensor_transform but not moved by its translation: the
/// origin is the lidar's optical centre, the axes Ouster's sensor frame (x forward, y left, z up).
/// range_m is the measured range, the beam angles those of the pixel's beam in the same frame,
/// intensity the reflectivity field, column the measurement_id, row the channel, time the
/// column's time stamp (the sensor's clock, seconds); object_id 0.
/// Throws InputError naming the file for anything that is not such a capture of this unit
/// (packets of another size or serial number, measurement ids beyond the frame, no packets).
std::vector<Frame> read_ouster_pcap(const std::filesystem::path& pcap, const OusterCalibration& calibration);

}  // namespace ladarsim
