#include "capture_file.h"

#include <cstdint>
#include <vector>

#include "ladarsim/core/input_error.h"

namespace ladarsim {
namespace {

constexpr std::uint32_t kLinkEthernet = 1;

// libpcap: a 24-byte file header, then a 16-byte header before each packet.
constexpr std::uint32_t kPcapMicroseconds = 0xa1b2c3d4u, kPcapNanoseconds = 0xa1b23c4du;
constexpr std::size_t kPcapHeader = 24, kPcapRecordHeader = 16;

// pcapng: blocks of type, total length, body, total length again.
constexpr std::uint32_t kSectionHeader = 0x0A0D0D0Au;  // the same in either byte order
constexpr std::uint32_t kByteOrderMagic = 0x1A2B3C4Du;
constexpr std::uint32_t kInterfaceDescription = 1, kObsoletePacket = 2, kSimplePacket = 3, kEnhancedPacket = 6;
constexpr std::uint16_t kOptionEnd = 0, kOptionTsResolution = 9, kOptionTsOffset = 14;
constexpr std::size_t kBlockOverhead = 12;

std::uint32_t swap32(std::uint32_t v) { return (v >> 24) | ((v >> 8) & 0xFF00u) | ((v << 8) & 0xFF0000u) | (v << 24); }

/// Integers of the file in its own byte order.
class Reader {
public:
    Reader(std::span<const unsigned char> bytes, bool big_endian) : b_(bytes), big_(big_endian) {}
    std::uint16_t u16(std::size_t o) const {
        return big_ ? static_cast<std::uint16_t>(b_[o] << 8 | b_[o + 1]) : static_cast<std::uint16_t>(b_[o + 1] << 8 | b_[o]);
    }
    std::uint32_t u32(std::size_t o) const {
        return big_ ? static_cast<std::uint32_t>(u16(o)) << 16 | u16(o + 2) : static_cast<std::uint32_t>(u16(o + 2)) << 16 | u16(o);
    }
    std::uint64_t u64(std::size_t o) const {
        return big_ ? static_cast<std::uint64_t>(u32(o)) << 32 | u32(o + 4) : static_cast<std::uint64_t>(u32(o + 4)) << 32 | u32(o);
    }

private:
    std::span<const unsigned char> b_;
    bool big_;
};

/// Seconds of a time stamp counting `units` a second: whole seconds and the fraction apart, so
/// that a microsecond stamp reads exactly as libpcap's seconds and microseconds do.
double seconds(std::uint64_t stamp, std::uint64_t units) {
    return static_cast<double>(stamp / units) + static_cast<double>(stamp % units) * (1.0 / static_cast<double>(units));
}

void read_pcap(std::span<const unsigned char> b, const std::string& name, const std::function<void(const CaptureRecord&)>& visit) {
    const std::uint32_t magic = Reader(b, false).u32(0);
    const bool big = magic == swap32(kPcapMicroseconds) || magic == swap32(kPcapNanoseconds);
    const Reader r(b, big);
    const std::uint64_t units = r.u32(0) == kPcapNanoseconds ? 1'000'000'000u : 1'000'000u;
    if (r.u32(20) != kLinkEthernet) throw InputError(name, "link type", "not Ethernet");
    std::size_t index = 0;
    for (std::size_t off = kPcapHeader; off < b.size();) {
        const std::string record = "record " + std::to_string(++index);
        if (off + kPcapRecordHeader > b.size()) throw InputError(name, record, "capture ends inside a record header");
        const double time_s = static_cast<double>(r.u32(off)) + seconds(r.u32(off + 4), units);
        const std::size_t length = r.u32(off + 8), wire_length = r.u32(off + 12);
        off += kPcapRecordHeader;
        if (length > b.size() - off) throw InputError(name, record, "capture ends inside a packet");
        visit(CaptureRecord{index, time_s, b.subspan(off, length), wire_length > length});
        off += length;
    }
}

/// A pcapng interface: what its packets' link type is and how their time stamps count.
struct Interface {
    std::uint32_t link_type = 0;
    std::uint64_t units = 1'000'000;  ///< time-stamp units a second (default: microseconds)
    double offset_s = 0.0;
};

Interface read_interface(const Reader& r, std::span<const unsigned char> body, const std::string& name, const std::string& block) {
    if (body.size() < 8) throw InputError(name, block, "interface description block cut short");
    Interface i;
    i.link_type = r.u16(0);
    for (std::size_t o = 8; o + 4 <= body.size();) {
        const std::uint16_t code = r.u16(o), length = r.u16(o + 2);
        o += 4;
        if (code == kOptionEnd) break;
        if (length > body.size() - o) throw InputError(name, block, "an option runs past its block");
        if (code == kOptionTsResolution && length >= 1) {
            const unsigned v = body[o];
            const unsigned power = v & 0x7Fu;
            if (v & 0x80u ? power > 63 : power > 19) throw InputError(name, block + ".if_tsresol", "beyond 64-bit time stamps");
            i.units = 1;
            for (unsigned k = 0; k < power; ++k) i.units *= v & 0x80u ? 2 : 10;
        } else if (code == kOptionTsOffset && length >= 8) {
            i.offset_s = static_cast<double>(static_cast<std::int64_t>(r.u64(o)));
        }
        o += (length + 3u) / 4u * 4u;
    }
    return i;
}

void read_pcapng(std::span<const unsigned char> b, const std::string& name, const std::function<void(const CaptureRecord&)>& visit) {
    std::vector<Interface> interfaces;  // of the current section
    bool big = false;                   // the current section's byte order
    std::size_t index = 0, blocks = 0;
    for (std::size_t off = 0; off < b.size();) {
        const std::string block = "block " + std::to_string(++blocks);
        if (b.size() - off < kBlockOverhead) throw InputError(name, block, "capture ends inside a block header");
        if (Reader(b, false).u32(off) == kSectionHeader) {
            // The section's byte-order magic says how to read the rest of it, its length included.
            if (b.size() - off < 16) throw InputError(name, block, "capture ends inside a section header");
            const std::uint32_t magic = Reader(b, false).u32(off + 8);
            if (magic != kByteOrderMagic && magic != swap32(kByteOrderMagic))
                throw InputError(name, block, "section header without its byte-order magic");
            big = magic != kByteOrderMagic;
            interfaces.clear();
        }
        const Reader r(b, big);
        const std::uint32_t type = r.u32(off);
        const std::size_t length = r.u32(off + 4);
        if (length < kBlockOverhead || length % 4 != 0)
            throw InputError(name, block, "block length " + std::to_string(length) + " is not a multiple of 4 from 12");
        if (length > b.size() - off) throw InputError(name, block, "capture ends inside a block");
        const auto body = b.subspan(off + 8, length - kBlockOverhead);
        const Reader in(body, big);
        off += length;
        if (type == kInterfaceDescription) {
            interfaces.push_back(read_interface(in, body, name, block));
            continue;
        }
        if (type == kSimplePacket)
            throw InputError(name, block, "a simple packet block carries no capture time: save the capture with enhanced packet blocks");
        if (type != kEnhancedPacket && type != kObsoletePacket) continue;  // statistics, name resolution, ...
        const std::string record = "record " + std::to_string(++index);
        if (body.size() < 20) throw InputError(name, record, "packet block cut short");
        // An obsolete packet block has a 16-bit interface id and a drop count where an enhanced one has its 32-bit id.
        const std::size_t id = type == kEnhancedPacket ? in.u32(0) : in.u16(0);
        if (id >= interfaces.size()) throw InputError(name, record, "interface " + std::to_string(id) + " is not described before its packets");
        const Interface& i = interfaces[id];
        if (i.link_type != kLinkEthernet) throw InputError(name, record, "interface " + std::to_string(id) + "'s link type is not Ethernet");
        const std::uint64_t stamp = static_cast<std::uint64_t>(in.u32(4)) << 32 | in.u32(8);
        const std::size_t captured = in.u32(12), wire_length = in.u32(16);
        if (captured > body.size() - 20) throw InputError(name, record, "packet runs past its block");
        visit(CaptureRecord{index, i.offset_s + seconds(stamp, i.units), body.subspan(20, captured), wire_length > captured});
    }
}

}  // namespace

void for_each_capture_record(std::span<const unsigned char> bytes, const std::string& name,
                             const std::function<void(const CaptureRecord&)>& visit) {
    const std::uint32_t magic = bytes.size() >= 4 ? Reader(bytes, false).u32(0) : 0;
    if (magic == kSectionHeader) return read_pcapng(bytes, name, visit);
    for (const std::uint32_t m : {kPcapMicroseconds, kPcapNanoseconds})
        if ((magic == m || magic == swap32(m)) && bytes.size() >= kPcapHeader) return read_pcap(bytes, name, visit);
    throw InputError(name, "magic", "neither a libpcap nor a pcapng capture");
}

}  // namespace ladarsim
