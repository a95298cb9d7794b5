#pragma once
// The link-layer records of a capture file in either format that tcpdump and Wireshark save:
// libpcap, or pcapng (Wireshark's default). What is inside a record is pcap_udp's business.
#include <cstddef>
#include <functional>
#include <span>
#include <string>

namespace ladarsim {

struct CaptureRecord {
    std::size_t index = 0;  ///< from 1, counting packets only (Wireshark's frame number)
    double time_s = 0.0;    ///< capture time, seconds since 1970
    std::span<const unsigned char> frame;  ///< the Ethernet frame as captured
    bool snapped = false;   ///< the capture kept less of the frame than went over the wire
};

/// Calls `visit` for every packet of `bytes`, in capture order. Reads libpcap in either byte order
/// with micro- or nanosecond time stamps, and pcapng: sections in either byte order, each
/// interface with its own link type, time-stamp resolution (if_tsresol) and offset (if_tsoffset),
/// packets in enhanced (or obsolete) packet blocks; blocks of other kinds are passed over. Throws
/// InputError naming `name` (and the record or block) for a file in neither format, a packet on a
/// link other than Ethernet, a simple packet block (it has no time stamp), or a file that ends
/// inside a record.
void for_each_capture_record(std::span<const unsigned char> bytes, const std::string& name,
                             const std::function<void(const CaptureRecord&)>& visit);

}  // namespace ladarsim
