#include "ladarsim/dataset/pcap_udp.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "capture_file.h"
#include "ladarsim/core/input_error.h"

namespace ladarsim {
namespace {

constexpr std::size_t kEthernetHeader = 14;
constexpr std::uint16_t kEtherTypeIpv4 = 0x0800;
constexpr unsigned kProtocolUdp = 17;
constexpr std::size_t kUdpHeader = 8;
// A sender emits one datagram's fragments back to back; a datagram still incomplete after this
// lost a fragment, and its IPv4 identification may come round again for a later one.
constexpr double kReassemblyTimeoutS = 1.0;

std::uint16_t be16(const unsigned char* p) { return static_cast<std::uint16_t>(p[0] << 8 | p[1]); }
std::uint32_t be32(const unsigned char* p) { return static_cast<std::uint32_t>(be16(p)) << 16 | be16(p + 2); }

/// A datagram whose fragments are still arriving. Fragment offsets count 8-byte blocks, so the
/// blocks received say when it is whole, whatever the order or duplication of its fragments.
struct Partial {
    double first_time_s = 0.0;
    std::vector<unsigned char> bytes;  ///< the IPv4 payload: UDP header first
    std::vector<bool> have;            ///< per 8-byte block
    std::size_t total = 0;             ///< payload length, known once the last fragment arrived

    bool complete() const {
        const std::size_t blocks = (total + 7) / 8;
        return total > 0 && have.size() >= blocks && std::all_of(have.begin(), have.begin() + static_cast<std::ptrdiff_t>(blocks), [](bool b) { return b; });
    }
};

class Capture {
public:
    Capture(std::string name, const std::function<void(const UdpDatagram&)>& visit) : name_(std::move(name)), visit_(visit) {}

    /// `snapped`: the capture kept less of the frame than went over the wire.
    void record(std::size_t index, double time_s, std::span<const unsigned char> frame, bool snapped) {
        if (frame.size() < kEthernetHeader + 20 || be16(&frame[12]) != kEtherTypeIpv4) return;
        const auto ip = frame.subspan(kEthernetHeader);
        const std::size_t header = (ip[0] & 0x0Fu) * 4u, length = be16(&ip[2]);
        if (ip[0] >> 4 != 4 || ip[9] != kProtocolUdp) return;
        if (header < 20 || length < header) fail(index, "IPv4 header lengths are inconsistent");
        if (length > ip.size()) {
            if (snapped) fail(index, "IPv4 packet cut short by the capture's snap length");
            return;  // the sender's header claims more than it sent (a VLP-16's position packets do)
        }
        const auto payload = ip.subspan(header, length - header);
        const std::uint16_t flags_offset = be16(&ip[6]);
        const bool more_fragments = flags_offset & 0x2000u;
        const std::size_t offset = (flags_offset & 0x1FFFu) * 8u;
        if (!more_fragments && offset == 0) return udp(index, time_s, payload);
        if (more_fragments && payload.size() % 8 != 0) fail(index, "an IPv4 fragment other than the last is not a whole number of 8-byte blocks");
        const auto key = std::make_tuple(be32(&ip[12]), be32(&ip[16]), be16(&ip[4]));
        Partial& p = partial_[key];
        if (!p.have.empty() && time_s - p.first_time_s > kReassemblyTimeoutS) p = Partial{};
        if (p.have.empty()) p.first_time_s = time_s;
        const std::size_t end = offset + payload.size();
        if (end > 65535 - 20) fail(index, "IPv4 fragment reaches beyond the largest datagram");
        if (p.bytes.size() < end) p.bytes.resize(end);
        if (p.have.size() < (end + 7) / 8) p.have.resize((end + 7) / 8);
        std::copy(payload.begin(), payload.end(), p.bytes.begin() + static_cast<std::ptrdiff_t>(offset));
        std::fill(p.have.begin() + static_cast<std::ptrdiff_t>(offset / 8), p.have.begin() + static_cast<std::ptrdiff_t>((end + 7) / 8), true);
        if (!more_fragments) p.total = end;
        if (!p.complete()) return;
        const Partial whole = std::move(p);
        partial_.erase(key);
        udp(index, time_s, std::span<const unsigned char>(whole.bytes).first(whole.total));
    }

private:
    void udp(std::size_t index, double time_s, std::span<const unsigned char> datagram) {
        if (datagram.size() < kUdpHeader) fail(index, "UDP header cut short");
        const std::size_t length = be16(&datagram[4]);
        if (length < kUdpHeader || length > datagram.size()) fail(index, "UDP length does not fit its IPv4 packet");
        visit_(UdpDatagram{index, time_s, be16(&datagram[2]), datagram.subspan(kUdpHeader, length - kUdpHeader)});
    }

    [[noreturn]] void fail(std::size_t index, const std::string& problem) const {
        throw InputError(name_, "record " + std::to_string(index), problem);
    }

    std::string name_;
    const std::function<void(const UdpDatagram&)>& visit_;
    std::map<std::tuple<std::uint32_t, std::uint32_t, std::uint16_t>, Partial> partial_;  // by source, destination, identification
};

}  // namespace

void for_each_udp_datagram(const std::filesystem::path& file, const std::function<void(const UdpDatagram&)>& visit) {
    const std::string name = file.string();
    std::ifstream in(file, std::ios::binary);
    if (!in) throw InputError(name, "(file)", "cannot open");
    const std::vector<unsigned char> b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    Capture capture(name, visit);
    for_each_capture_record(b, name, [&](const CaptureRecord& r) { capture.record(r.index, r.time_s, r.frame, r.snapped); });
}

}  // namespace ladarsim
