#pragma once
// UDP datagrams out of a libpcap or pcapng capture: what every recorded-lidar decoder reads before
// its own packet format begins (no Debian library reads pcap without pulling in a capture stack).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <span>

namespace ladarsim {

struct UdpDatagram {
    std::size_t record = 0;             ///< capture record that completed it, from 1 (Wireshark's frame number)
    double time_s = 0.0;                ///< capture time of that record, seconds since 1970
    std::uint16_t destination_port = 0;
    std::span<const unsigned char> payload;  ///< valid only while the visitor runs
};

/// Calls `visit` for every UDP datagram over IPv4 in a capture of Ethernet frames, in capture
/// order: libpcap (either byte order, micro- or nanosecond time stamps) or pcapng (Wireshark's
/// default; dataset/src/capture_file.h says what of it is read). A datagram larger than the link's
/// MTU arrives as IPv4 fragments: it is reassembled and visited when its last missing fragment
/// arrives; one that never completes is not visited. Other traffic, and packets whose IPv4 header
/// claims more than the wire carried, are skipped. Throws InputError naming the file (and the
/// record) for anything that is not such a capture, or that the capture's snap length cut short;
/// an InputError the visitor throws passes through.
void for_each_udp_datagram(const std::filesystem::path& file, const std::function<void(const UdpDatagram&)>& visit);

/// The T at `offset` of a payload, in the little-endian order the lidars send (and this host uses).
template <typename T>
T read_le(std::span<const unsigned char> payload, std::size_t offset) {
    T v;
    std::memcpy(&v, payload.data() + offset, sizeof v);
    return v;
}

}  // namespace ladarsim
