#pragma once
// Captures written by hand for the pcap tests: little-endian microsecond libpcap files of
// Ethernet frames, the same records as pcapng (either byte order, any time-stamp resolution), UDP over IPv4 split into fragments the way a host sends a datagram larger
// than its MTU, and the records of an existing capture read back.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace ladarsim::test {

using Bytes = std::vector<unsigned char>;

struct PcapRecord {
    std::uint32_t seconds = 0, microseconds = 0;
    Bytes frame;                    ///< as captured
    std::uint32_t wire_length = 0;  ///< 0: the frame's own length
};

inline void put_le32(Bytes& b, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) b.push_back(static_cast<unsigned char>(v >> (8 * i)));
}
inline void put_be16(Bytes& b, std::uint16_t v) {
    b.push_back(static_cast<unsigned char>(v >> 8));
    b.push_back(static_cast<unsigned char>(v));
}

inline void write_pcap(const std::filesystem::path& file, const std::vector<PcapRecord>& records, std::uint32_t link_type = 1) {
    Bytes b;
    put_le32(b, 0xa1b2c3d4u);
    for (const unsigned char c : {2, 0, 4, 0}) b.push_back(c);  // version 2.4
    put_le32(b, 0);                   // time zone
    put_le32(b, 0);                   // time stamp accuracy
    put_le32(b, 65535);               // snap length
    put_le32(b, link_type);
    for (const PcapRecord& r : records) {
        put_le32(b, r.seconds);
        put_le32(b, r.microseconds);
        put_le32(b, static_cast<std::uint32_t>(r.frame.size()));
        put_le32(b, r.wire_length ? r.wire_length : static_cast<std::uint32_t>(r.frame.size()));
        b.insert(b.end(), r.frame.begin(), r.frame.end());
    }
    std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

/// How write_pcapng lays its file out.
struct PcapngLayout {
    bool big_endian = false;
    int nanoseconds = 0;           ///< 1: if_tsresol 9 (nanosecond time stamps); 0: the default microseconds
    std::uint32_t link_type = 1;
    bool extra_blocks = true;      ///< a name-resolution and a statistics block, which readers pass over
    bool simple_packets = false;   ///< simple packet blocks (no time stamp) in place of enhanced ones
    bool obsolete_packets = false; ///< packet blocks (pcapng 1.0's, before enhanced ones) in their place
};

/// `records` as Wireshark saves them: a section header, an interface description, one enhanced
/// packet block a record (a second section, in the other byte order, holds the second half).
inline void write_pcapng(const std::filesystem::path& file, const std::vector<PcapRecord>& records, const PcapngLayout& layout = {}) {
    Bytes out;
    bool big = layout.big_endian;
    auto u16 = [&](Bytes& b, std::uint16_t v) {
        for (int i = 0; i < 2; ++i) b.push_back(static_cast<unsigned char>(v >> (big ? 8 - 8 * i : 8 * i)));
    };
    auto u32 = [&](Bytes& b, std::uint32_t v) {
        for (int i = 0; i < 4; ++i) b.push_back(static_cast<unsigned char>(v >> (big ? 24 - 8 * i : 8 * i)));
    };
    auto block = [&](std::uint32_t type, Bytes body) {
        while (body.size() % 4) body.push_back(0);
        const auto length = static_cast<std::uint32_t>(body.size() + 12);
        u32(out, type);
        u32(out, length);
        out.insert(out.end(), body.begin(), body.end());
        u32(out, length);
    };
    auto section = [&] {
        Bytes shb;
        u32(shb, 0x1A2B3C4Du);
        u16(shb, 1);
        u16(shb, 0);
        for (int i = 0; i < 8; ++i) shb.push_back(0xFF);  // section length: not given
        block(0x0A0D0D0Au, shb);
        Bytes idb;
        u16(idb, static_cast<std::uint16_t>(layout.link_type));
        u16(idb, 0);
        u32(idb, 65535);
        if (layout.nanoseconds) {
            u16(idb, 9);  // if_tsresol
            u16(idb, 1);
            idb.insert(idb.end(), {9, 0, 0, 0});
        }
        u16(idb, 0);  // opt_endofopt
        u16(idb, 0);
        block(1, idb);
    };
    section();
    for (std::size_t n = 0; n < records.size(); ++n) {
        const PcapRecord& r = records[n];
        if (n > 0 && n == records.size() / 2) {
            big = !big;
            section();
        }
        if (layout.extra_blocks && n == 1) {
            Bytes nrb;  // a name-resolution block holding only its end of records
            u32(nrb, 0);
            block(4, nrb);
        }
        const auto wire = r.wire_length ? r.wire_length : static_cast<std::uint32_t>(r.frame.size());
        Bytes body;
        if (layout.simple_packets) {
            u32(body, wire);
            body.insert(body.end(), r.frame.begin(), r.frame.end());
            block(3, body);
            continue;
        }
        const std::uint64_t stamp = layout.nanoseconds ? r.seconds * 1'000'000'000ull + r.microseconds * 1000ull
                                                       : r.seconds * 1'000'000ull + r.microseconds;
        if (layout.obsolete_packets) {
            u16(body, 0);  // interface
            u16(body, 0);  // drops
        } else {
            u32(body, 0);  // interface
        }
        u32(body, static_cast<std::uint32_t>(stamp >> 32));
        u32(body, static_cast<std::uint32_t>(stamp));
        u32(body, static_cast<std::uint32_t>(r.frame.size()));
        u32(body, wire);
        body.insert(body.end(), r.frame.begin(), r.frame.end());
        block(layout.obsolete_packets ? 2 : 6, body);
    }
    if (layout.extra_blocks) {
        Bytes isb;  // interface statistics: interface 0, time stamp 0, no options
        for (int i = 0; i < 12; ++i) isb.push_back(0);
        block(5, isb);
    }
    std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(out.data()), static_cast<std::streamsize>(out.size()));
}

/// The records of a capture written as above (or by tcpdump on a little-endian host).
inline std::vector<PcapRecord> read_pcap_records(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    const Bytes b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    auto le32 = [&](std::size_t o) {
        std::uint32_t v;
        std::memcpy(&v, &b[o], 4);
        return v;
    };
    std::vector<PcapRecord> records;
    for (std::size_t off = 24; off + 16 <= b.size();) {
        PcapRecord r{le32(off), le32(off + 4), {}, le32(off + 12)};
        const std::size_t length = le32(off + 8);
        r.frame.assign(b.begin() + static_cast<std::ptrdiff_t>(off + 16), b.begin() + static_cast<std::ptrdiff_t>(off + 16 + length));
        records.push_back(std::move(r));
        off += 16 + length;
    }
    return records;
}

/// Ethernet frames carrying one UDP datagram over IPv4, in fragments of at most `mtu` bytes of
/// IPv4 packet (every fragment but the last a whole number of 8-byte blocks), in sending order.
inline std::vector<Bytes> udp_fragments(const Bytes& payload, std::uint16_t port, std::uint16_t identification, std::size_t mtu = 1500) {
    if (payload.size() > 65535 - 20 - 8) throw std::invalid_argument("datagram too large for IPv4");
    Bytes datagram;  // UDP header and payload: what the fragments share out
    put_be16(datagram, port);
    put_be16(datagram, port);
    put_be16(datagram, static_cast<std::uint16_t>(8 + payload.size()));
    put_be16(datagram, 0);  // no checksum
    datagram.insert(datagram.end(), payload.begin(), payload.end());
    const std::size_t per_fragment = (mtu - 20) / 8 * 8;
    std::vector<Bytes> frames;
    for (std::size_t offset = 0; offset < datagram.size(); offset += per_fragment) {
        const std::size_t length = std::min(per_fragment, datagram.size() - offset);
        const bool more = offset + length < datagram.size();
        Bytes f(12, 0xAA);  // destination and source MAC addresses
        put_be16(f, 0x0800);
        f.insert(f.end(), {0x45, 0});
        put_be16(f, static_cast<std::uint16_t>(20 + length));
        put_be16(f, identification);
        put_be16(f, static_cast<std::uint16_t>((more ? 0x2000 : 0) | offset / 8));
        f.insert(f.end(), {64, 17, 0, 0, 192, 168, 1, 10, 192, 168, 1, 1});  // TTL, UDP, checksum, addresses
        f.insert(f.end(), datagram.begin() + static_cast<std::ptrdiff_t>(offset), datagram.begin() + static_cast<std::ptrdiff_t>(offset + length));
        frames.push_back(std::move(f));
    }
    return frames;
}

}  // namespace ladarsim::test
