#pragma once
// The UDP datagrams of a capture copied out of the visitor, for the pcap tests to compare.
#include <filesystem>
#include <vector>

#include "ladarsim/dataset/pcap_udp.h"
#include "pcap_writer.h"

namespace ladarsim::test {

struct SeenDatagram {
    std::size_t record;
    double time_s;
    std::uint16_t port;
    Bytes payload;
};

inline std::vector<SeenDatagram> datagrams(const std::filesystem::path& file) {
    std::vector<SeenDatagram> seen;
    for_each_udp_datagram(file, [&](const UdpDatagram& d) {
        seen.push_back({d.record, d.time_s, d.destination_port, Bytes(d.payload.begin(), d.payload.end())});
    });
    return seen;
}

}  // namespace ladarsim::test
