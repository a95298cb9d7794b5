#pragma once
// Recorded frames from a real sensor: Velodyne VLP-16 packets in a libpcap capture, decoded into
// the frame format (no Debian library reads them).
#include <filesystem>
#include <vector>

#include "ladarsim/dataset/frame.h"

namespace ladarsim {

/// Decodes the VLP-16 data packets of a pcap file (Ethernet/IPv4/UDP, 1206-byte payloads of 12
/// blocks, each an azimuth and two firing sequences of 16 channels; 2 mm range units) into frames,
/// one per revolution (a new frame where the azimuth wraps). Channel elevations are the VLP-16's
/// (-15, 1, -13, 3, ... 15 deg): the packets' factory byte may say otherwise, the ground rings decide.
/// Points are in ladarsim's sensor frame (x forward = Velodyne's y, y left, z up), intensity is the
/// sensor's calibrated reflectivity byte, column the firing sequence, row the channel from the top,
/// time from the packet time stamps; object_id 0 (a recording has no ground truth).
/// Throws InputError naming the file for anything that is not such a capture.
std::vector<Frame> read_velodyne_vlp16_pcap(const std::filesystem::path& file);

}  // namespace ladarsim
