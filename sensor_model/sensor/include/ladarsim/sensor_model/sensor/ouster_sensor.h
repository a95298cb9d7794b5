#pragma once
// An Ouster unit as a ladarsim sensor, made from its own metadata (calibration) file alone.
#include <nlohmann/json.hpp>

#include "ladarsim/dataset/ouster_pcap.h"

namespace ladarsim::sensor_model {

/// The unit as a ladarsim sensor document: a channel_table scan whose column k, channel c points
/// where read_ouster_pcap puts the beam of measurement_id k, channel c. Geometry and timing are
/// the calibration's; Ouster publishes little radiometry, so most of it is an estimate.
/// Throws InputError naming the metadata file for a product line it has no figures for, or a
/// lidar_to_sensor_transform that tilts the lidar (a channel table turns about z only).
nlohmann::json ouster_sensor_json(const OusterCalibration& calibration);

}  // namespace ladarsim::sensor_model
